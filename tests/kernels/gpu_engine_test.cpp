// GPU engine against the CPU engine on the same inputs: each step on random inputs, then whole
// meshes of G1-G5. Skips with a message where no CUDA device is visible (CI).
#include "kernels/gpu_engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <utility>

#include "core/common/error.h"
#include "core/delaunay/exact_predicates.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/validity.h"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

using testing::expect_meshes_agree;
using testing::load_and_triangulate;
using testing::point_gaps;
using testing::PointGaps;
using testing::random_points;

using Triangles = std::vector<std::array<int32_t, 3>>;

std::set<std::array<int32_t, 3>> canonical(const Triangles& tris) {
  std::set<std::array<int32_t, 3>> out;
  for (auto t : tris) {
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

CompiledProblem compiled(const std::string& id, double nodes) {
  Problem p = testing::benchmark_problem(id, 0.1);
  p.h0 = h0_for_node_count(p, nodes);
  return compile_problem(p);
}

class GpuAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(GpuAgreement, InitialPointsMatchTheCpu) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 5000);
  ThreadPool pool;
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  const int64_t n_cpu = cpu.initialize(c), n_gpu = gpu.initialize(c);
  // Both use the same evaluator and hash; nvcc's fused multiply-adds may move a point across the
  // geps or rejection threshold, so a handful may differ.
  EXPECT_NEAR(n_gpu, n_cpu, std::max<int64_t>(2, n_cpu / 1000));
  std::vector<Vec2> a, b;
  cpu.read_points(a);
  gpu.read_points(b);
  for (size_t f = 0; f < c.fixed_points.size(); ++f) EXPECT_EQ(b[f], c.fixed_points[f]);
}

TEST_P(GpuAgreement, OneStepOnRandomPointsMatchesTheCpu) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 3000);
  ThreadPool pool;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const auto pts = random_points(c, 3000, seed);
    CpuEngine cpu(pool);
    GpuEngine gpu(0);
    cpu.load_points(c, pts);
    gpu.load_points(c, pts);
    const TopologyStats tc = cpu.retriangulate(true), tg = gpu.retriangulate(true);
    EXPECT_EQ(tc.triangles, tg.triangles);
    EXPECT_EQ(tc.bars, tg.bars);
    Triangles t_cpu, t_gpu;
    cpu.read_triangles(t_cpu);
    gpu.read_triangles(t_gpu);
    EXPECT_EQ(canonical(t_cpu), canonical(t_gpu));
    const StepResult sc = cpu.move_points(), sg = gpu.move_points();
    EXPECT_NEAR(sc.max_move, sg.max_move, 1e-9);
    EXPECT_NEAR(sc.rms_move, sg.rms_move, 1e-9);
    EXPECT_NEAR(sc.max_drift, sg.max_drift, 1e-9);
    std::vector<Vec2> a, b;
    cpu.read_points(a);
    gpu.read_points(b);
    ASSERT_EQ(a.size(), b.size());
    const PointGaps gaps = point_gaps(c, a, b);
    EXPECT_LT(gaps.interior, 1e-12 * c.h0) << "seed " << seed;
    EXPECT_LT(gaps.boundary, 1e-6 * c.h0) << "seed " << seed;
  }
}

// A batch of steps on the device, in one cooperative launch or through the step graph's loop:
// the same bits as the same kernels launched one by one, one step per call, and it stops exactly
// after the first step at which the loop's rule stops (the positions swap after every step, so
// an odd count checks the hand-back as well).
TEST_P(GpuAgreement, StepGraphRunsTheSameStepsAsOneAtATime) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 3000);
  const auto pts = random_points(c, 3000, 7);
  for (const auto& [lagged, together] : {std::pair{true, true}, std::pair{true, false},
                                         std::pair{false, true}, std::pair{false, false}}) {
    for (const double ttol : {1e9, 0.03}) {
      GpuEngine graph(0), direct(0);
      graph.set_step_graph(true);
      graph.set_steps_together(together);
      direct.set_step_graph(false);
      EXPECT_EQ(graph.preferred_batch(), 32);
      EXPECT_EQ(direct.preferred_batch(), 1);
      graph.set_lagged_scale(lagged);
      direct.set_lagged_scale(lagged);
      load_and_triangulate(c, pts, {&graph, &direct});
      StepRule rule;
      rule.ttol = ttol;
      rule.min_iterations = 1 << 30;  // never converged
      std::vector<StepResult> steps;
      graph.move_points_until(rule, 1, 40, steps);
      std::vector<StepResult> expected;
      for (int k = 0; k < 40; ++k) {
        expected.push_back(direct.move_points());
        if (rule.stops(expected.back(), 1 + k, Settling{})) break;
      }
      const std::string where = "lagged " + std::to_string(lagged) + " together " +
                                std::to_string(together) + " ttol " + std::to_string(ttol);
      ASSERT_EQ(steps.size(), expected.size()) << where;
      if (ttol > 1.0) {
        EXPECT_EQ(steps.size(), 40u) << where;
      } else {
        EXPECT_LT(steps.size(), 40u) << where << ": the drift test never stopped the batch";
      }
      for (size_t k = 0; k < steps.size(); ++k) {
        EXPECT_EQ(steps[k].max_move, expected[k].max_move) << where << " step " << k;
        EXPECT_EQ(steps[k].max_drift, expected[k].max_drift) << where << " step " << k;
        EXPECT_EQ(steps[k].rms_move, expected[k].rms_move) << where << " step " << k;
      }
      std::vector<Vec2> a, b;
      graph.read_points(a);
      direct.read_points(b);
      EXPECT_EQ(a, b) << where;
    }
  }
}

// One batch of up to 32 steps through the step graph, from iteration 1, on 3,000 random points
// of `geometry`, under `rule` (its ttol made too large to end the batch).
std::vector<StepResult> graph_batch(const std::string& geometry, StepRule rule) {
  const CompiledProblem c = compiled(geometry, 3000);
  const auto pts = random_points(c, 3000, 7);
  GpuEngine graph(0);
  graph.set_step_graph(true);
  load_and_triangulate(c, pts, {&graph});
  rule.ttol = 1e9;
  std::vector<StepResult> steps;
  graph.move_points_until(rule, 1, 32, steps);
  return steps;
}

// The settling record (step_rule.cuh) is carried on inside a batch on the device from the loop's
// record before it: with every step settled, no step's largest move small enough and none a new
// low, a patience of 5 with 2 stalled steps before the batch ends it at its third step, as the
// loop would.
TEST_P(GpuAgreement, StepGraphStopsWhenThePatienceRunsOut) {
  SKIP_WITHOUT_GPU();
  StepRule rule;
  rule.dptol = 1e9;            // every step settled
  rule.max_move_factor = 0.0;  // ... but none with its largest move small enough
  rule.patience = 5;
  rule.settling = {0.0, 2};  // no move falls under 0
  EXPECT_EQ(graph_batch(GetParam(), rule).size(), 3u);
}

// A coarser level's rms record (StepRule::rms_patience) is carried through the graph the same
// way: with two steps stalled before the batch and a patience of 5, it ends at its third step.
TEST_P(GpuAgreement, StepGraphStopsWhenTheRmsPatienceRunsOut) {
  SKIP_WITHOUT_GPU();
  StepRule rule;
  rule.dptol = 0.0;  // never settled
  rule.rms_patience = 5;
  rule.settling.rms_record = 0.0;  // no rms move falls under a record of 0
  rule.settling.rms_stalled = 2;
  EXPECT_EQ(graph_batch(GetParam(), rule).size(), 3u);
}

// Two runs that must be the same bits: the same steps and the same mesh.
void expect_same_run(const MeshResult& a, const MeshResult& b) {
  EXPECT_EQ(a.stats.iterations, b.stats.iterations);
  EXPECT_EQ(a.stats.cleanup_iterations, b.stats.cleanup_iterations);
  EXPECT_EQ(a.stats.retriangulations, b.stats.retriangulations);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
}

// The loop asks the graph for batches of steps (engine.h): the whole job runs the same
// iterations and gives the same mesh, bit for bit, as with one step per round trip.
TEST_P(GpuAgreement, StepGraphGivesTheSameMesh) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 5000);
  GpuEngine graph(0), direct(0);
  graph.set_step_graph(true);
  direct.set_step_graph(false);
  expect_same_run(generate_mesh(c, graph, nullptr, nullptr),
                  generate_mesh(c, direct, nullptr, nullptr));
}

// A batch's steps in one cooperative launch and through the step graph's loop: the same job,
// bit for bit.
TEST_P(GpuAgreement, StepsTogetherGiveTheGraphLoopsMesh) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 5000);
  GpuEngine together(0), loop(0);
  together.set_steps_together(true);
  loop.set_steps_together(false);
  expect_same_run(generate_mesh(c, together, nullptr, nullptr),
                  generate_mesh(c, loop, nullptr, nullptr));
}

// The clearance (clearance.cuh) skips the distance far inside the domain; evaluating it at every
// node and centroid (an infinite slope bound) gives the same bits on the device too.
TEST_P(GpuAgreement, ClearanceLeavesTheMeshBitForBit) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem carried = compiled(GetParam(), 5000);
  CompiledProblem evaluated = carried;
  evaluated.lipschitz = INFINITY;
  GpuEngine first(0), second(0);
  expect_same_run(generate_mesh(carried, first, nullptr, nullptr),
                  generate_mesh(evaluated, second, nullptr, nullptr));
}

// The GPU engine's points and kept triangles, as many triangles as CGAL keeps when it
// triangulates those points from scratch, up to the collapsed boundary slivers a repair drops.
struct GpuMesh {
  std::vector<Vec2> points;
  Triangles triangles;
};
GpuMesh read_beside_cgal(const CompiledProblem& c, GpuEngine& gpu, ThreadPool& pool,
                         const std::string& where) {
  GpuMesh m;
  gpu.read_points(m.points);
  gpu.read_triangles(m.triangles);
  CpuEngine cpu(pool);
  cpu.load_points(c, m.points);
  cpu.retriangulate(true);
  Triangles t_cpu;
  cpu.read_triangles(t_cpu);
  EXPECT_NEAR(static_cast<double>(m.triangles.size()), static_cast<double>(t_cpu.size()),
              0.01 * t_cpu.size())
      << where;
  return m;
}

// The repaired triangulation must be Delaunay: every kept triangle counter-clockwise and every
// edge between two kept triangles locally Delaunay (exact predicates), with as many triangles as
// CGAL's rebuild of the same points, up to the collapsed boundary slivers a repair drops.
TEST_P(GpuAgreement, RepairByFlipsGivesADelaunayTriangulation) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 3000);
  ThreadPool pool;
  GpuEngine gpu(0);
  gpu.initialize(c);
  gpu.retriangulate(true);
  int64_t total_flips = 0, repairs = 0;
  for (int step = 0; step < 60; ++step) {
    for (int i = 0; i < 3; ++i) gpu.move_points();
    const TopologyStats tg = gpu.retriangulate(false);
    if (tg.full) continue;
    ++repairs;
    total_flips += tg.flips;
    const auto [pts, t_gpu] = read_beside_cgal(c, gpu, pool, "step " + std::to_string(step));
    std::map<std::array<int32_t, 2>, std::pair<int32_t, int32_t>>
        opposite;  // edge -> (tri, vertex)
    for (size_t t = 0; t < t_gpu.size(); ++t) {
      const auto& tri = t_gpu[t];
      ASSERT_GT(orientation_sign(pts[tri[0]], pts[tri[1]], pts[tri[2]]), 0) << "step " << step;
      for (int k = 0; k < 3; ++k) {
        const int32_t a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
        const auto it = opposite.find({b, a});
        if (it == opposite.end()) {
          opposite[{a, b}] = {static_cast<int32_t>(t), tri[k]};
          continue;
        }
        EXPECT_LE(in_circle_sign(pts[tri[0]], pts[tri[1]], pts[tri[2]], pts[it->second.second]), 0)
            << "edge " << a << "-" << b << " is not locally Delaunay at step " << step;
      }
    }
  }
  EXPECT_GT(repairs, 10);
  EXPECT_GT(total_flips, 0) << "the test never exercised a flip";
}

// Thirty repairs of G2's moving nodes on an engine set up by the caller: none falls back to a
// rebuild, some flip, and the result is the triangulation CGAL builds from scratch, up to dropped
// boundary slivers.
void expect_repairs_like_cgal(GpuEngine& gpu) {
  const CompiledProblem c = compiled("G2", 3000);
  ThreadPool pool;
  gpu.initialize(c);
  gpu.retriangulate(true);
  int64_t flips = 0;
  for (int step = 0; step < 30; ++step) {
    for (int i = 0; i < 3; ++i) gpu.move_points();
    const TopologyStats tg = gpu.retriangulate(false);
    EXPECT_FALSE(tg.repair_failed) << "step " << step;
    flips += tg.flips;
  }
  EXPECT_GT(flips, 0) << "the test never exercised a flip";
  read_beside_cgal(c, gpu, pool, "after the repairs");
}

// A repair whose rounds outlast one launch of the flip loop launches it again: with one round a
// launch, every repair that flips needs several launches.
TEST(GpuRepair, RoundsThatOutlastOneLaunchOfTheFlipLoopGoOn) {
  SKIP_WITHOUT_GPU();
  GpuEngine gpu(0);
  gpu.set_flip_rounds_per_launch(1);
  expect_repairs_like_cgal(gpu);
}

// The flip loop hands a round whose list is short to one block (flip_round.h), and gives a tail
// that grows back to the grid through a new launch: no round, few rounds or every round after a
// repair's first in the one block.
class GpuFlipTail : public ::testing::TestWithParam<int> {};

TEST_P(GpuFlipTail, RepairsEndDelaunayWhateverTheTailTakes) {
  SKIP_WITHOUT_GPU();
  GpuEngine gpu(0);
  gpu.set_flip_tail_items(GetParam());
  expect_repairs_like_cgal(gpu);
}

INSTANTIATE_TEST_SUITE_P(TailItems, GpuFlipTail, ::testing::Values(0, 2, 1 << 30));

// A multilevel step: a coarse mesh relaxed at 2 h0 and split in four (refine.h). The device
// refines it to the host's points, bit for bit and in the same order, and flips its split
// triangles, with no rebuild, to the triangulation that CGAL builds from scratch on them.
TEST_P(GpuAgreement, RefinedLevelFlipsToTheSameTriangulation) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem fine = compiled(GetParam(), 8000);
  CompiledProblem coarse = fine;
  coarse.h0 = 2 * fine.h0;
  ThreadPool pool;
  CpuEngine relax(pool);
  generate_mesh(coarse, relax, nullptr, nullptr);
  std::vector<Vec2> pts;
  relax.read_points(pts);
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  load_and_triangulate(coarse, pts, {&cpu, &gpu});
  const int64_t n_cpu = cpu.refine(fine), n_gpu = gpu.refine(fine);
  EXPECT_GT(n_cpu, 3 * static_cast<int64_t>(pts.size()));
  ASSERT_EQ(n_gpu, n_cpu);
  std::vector<Vec2> p_cpu, p_gpu;
  cpu.read_points(p_cpu);
  gpu.read_points(p_gpu);
  EXPECT_TRUE(std::equal(p_cpu.begin(), p_cpu.end(), p_gpu.begin()));
  cpu.retriangulate(true);
  const TopologyStats tg = gpu.retriangulate(true);
  EXPECT_FALSE(tg.repair_failed) << "the device rebuilt instead of flipping";
  EXPECT_GT(tg.flips, 0);
  Triangles t_cpu, t_gpu;
  cpu.read_triangles(t_cpu);
  gpu.read_triangles(t_gpu);
  const auto sorted = [](Triangles t) {
    for (auto& tri : t)
      std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    std::sort(t.begin(), t.end());
    return t;
  };
  EXPECT_EQ(sorted(t_gpu), sorted(t_cpu));
}

TEST_P(GpuAgreement, DensityControlRemovesTheSamePoints) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 2000);
  ThreadPool pool;
  // Crowd the domain: twice the points it wants.
  const auto pts = random_points(c, 4000, 7);
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  load_and_triangulate(c, pts, {&cpu, &gpu});
  const int64_t rc = cpu.remove_crowded_points(kRemoveAny),
                rg = gpu.remove_crowded_points(kRemoveAny);
  EXPECT_GT(rc, 0);
  EXPECT_EQ(rc, rg);
  std::vector<Vec2> a, b;
  cpu.read_points(a);
  gpu.read_points(b);
  EXPECT_EQ(a.size(), b.size());
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
}

// The clean-up's removal, found on the device, against the host's rule on the same points and
// triangulation: the same nodes go. Forty steps from random points leave every geometry's
// boundary with slivers (39-68 at 2,000 nodes; the dithered initial grid leaves none).
TEST_P(GpuAgreement, CleanupRemovesTheSameSlivers) {
  SKIP_WITHOUT_GPU();
  CompiledProblem c = compiled(GetParam(), 2000);
  c.params.fscale = kUniformFscale;  // distmesh2d.m's push
  ThreadPool pool;
  CpuEngine relax(pool);
  relax.load_points(c, random_points(c, 2000, 1));
  relax.retriangulate(true);
  for (int i = 1; i <= 40; ++i) {
    relax.move_points();
    if (i % 10 == 0) relax.retriangulate(false);
  }
  std::vector<Vec2> pts;
  relax.read_points(pts);
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  load_and_triangulate(c, pts, {&cpu, &gpu});
  const int64_t rc = cpu.remove_boundary_slivers(c, kRemoveAny),
                rg = gpu.remove_boundary_slivers(c, kRemoveAny);
  EXPECT_EQ(rc, rg);
  EXPECT_GT(rc, 0) << "the test no longer exercises a removal";
  std::vector<Vec2> a, b;
  cpu.read_points(a);
  gpu.read_points(b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
  // And the next full triangulation completes what survived.
  cpu.retriangulate(true);
  const TopologyStats tg = gpu.retriangulate(true);
  EXPECT_FALSE(tg.repair_failed);
}

TEST_P(GpuAgreement, WholeMeshMatchesTheCpuEngine) {
  SKIP_WITHOUT_GPU();
  const std::string id = GetParam();
  for (double nodes : {2000.0, 20000.0}) {
    const CompiledProblem c = compiled(id, nodes);
    ThreadPool pool;
    CpuEngine cpu(pool);
    GpuEngine gpu(0);
    const MeshResult rc = generate_mesh(c, cpu, nullptr, nullptr);
    const MeshResult rg = generate_mesh(c, gpu, nullptr, nullptr);
    SCOPED_TRACE(id + " at " + std::to_string(nodes) + " nodes");
    const auto validity = check_validity(rg.mesh);
    EXPECT_TRUE(validity.problems.empty()) << validity.problems.front();
    EXPECT_NEAR(static_cast<double>(rg.mesh.points.size()),
                static_cast<double>(rc.mesh.points.size()), 0.02 * rc.mesh.points.size());
    EXPECT_NEAR(rg.quality.q_mean, rc.quality.q_mean, 0.01);
    EXPECT_GE(rg.quality.q_min, rc.quality.q_min - 0.05);
    EXPECT_GE(rg.quality.q_min, 0.65);
    EXPECT_NEAR(mesh_area(rg.mesh), testing::benchmark_area(id),
                0.005 * testing::benchmark_area(id));
    EXPECT_TRUE(rg.stats.converged);
    for (const Vec2 f : c.fixed_points) {
      EXPECT_NE(std::find(rg.mesh.points.begin(), rg.mesh.points.end(), f), rg.mesh.points.end());
    }
    EXPECT_EQ(rg.mesh.boundary_names, rc.mesh.boundary_names);
  }
}

// Float atomics sum in another order every run: the same mesh up to rounding.
TEST_P(GpuAgreement, AtomicForceSumsAgreeWithTheGather) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled(GetParam(), 3000);
  const auto pts = random_points(c, 3000, 11);
  GpuEngine gather(0), atomic(0);
  atomic.set_force_sum(GpuEngine::ForceSum::kAtomic);
  load_and_triangulate(c, pts, {&gather, &atomic});
  const StepResult sg = gather.move_points(), sa = atomic.move_points();
  EXPECT_NEAR(sg.rms_move, sa.rms_move, 1e-9);
  std::vector<Vec2> a, b;
  gather.read_points(a);
  atomic.read_points(b);
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, norm(a[i] - b[i]));
  EXPECT_LT(worst, 1e-6 * c.h0);
  const MeshResult whole = generate_mesh(c, atomic, nullptr, nullptr);
  EXPECT_TRUE(check_validity(whole.mesh).problems.empty());
  EXPECT_GE(whole.quality.q_min, 0.65);
}

// The one-pass step (L0 scale one step old, the default) against a pass over the bars every
// step: the same mesh within the bounds that hold the GPU engine to the CPU engine.
TEST_P(GpuAgreement, LaggedScaleKeepsTheMesh) {
  SKIP_WITHOUT_GPU();
  const std::string id = GetParam();
  const CompiledProblem c = compiled(id, 20000);
  GpuEngine exact(0), lagged(0);
  exact.set_lagged_scale(false);
  const MeshResult re = generate_mesh(c, exact, nullptr, nullptr);
  const MeshResult rl = generate_mesh(c, lagged, nullptr, nullptr);
  const auto validity = check_validity(rl.mesh);
  EXPECT_TRUE(validity.problems.empty()) << validity.problems.front();
  EXPECT_NEAR(static_cast<double>(rl.mesh.points.size()),
              static_cast<double>(re.mesh.points.size()), 0.02 * re.mesh.points.size());
  EXPECT_NEAR(rl.quality.q_mean, re.quality.q_mean, 0.01);
  EXPECT_GE(rl.quality.q_min, re.quality.q_min - 0.05);
  EXPECT_TRUE(rl.stats.converged);
}

INSTANTIATE_TEST_SUITE_P(Geometries, GpuAgreement, ::testing::Values("G1", "G2", "G3", "G4", "G5"));

// Whole meshes of `c` on both engines agree, boundary names included.
void expect_engines_agree(const CompiledProblem& c) {
  ThreadPool pool;
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  const MeshResult rc = generate_mesh(c, cpu, nullptr, nullptr);
  const MeshResult rg = generate_mesh(c, gpu, nullptr, nullptr);
  expect_meshes_agree(rc, rg);
  EXPECT_EQ(rg.mesh.boundary_names, rc.mesh.boundary_names);
}

// The spatial indexes on the device (bvh.h): a square minus 60 disks (an indexed difference)
// and minus a lake whose shore is a polygon of 400 vertices (an indexed polygon), graded
// toward the lake through the same polygon. The device evaluates them as the host does.
TEST(GpuIndexedGeometry, ManyHolesAndALongPolygonMatchTheCpuEngine) {
  SKIP_WITHOUT_GPU();
  std::vector<Vec2> shore;
  for (int k = 0; k < 400; ++k) {
    const double a = 2 * std::numbers::pi * k / 400, r = 1.5 * (1 + 0.2 * std::sin(5 * a));
    shore.push_back({5 + r * std::cos(a), 5 + r * std::sin(a)});
  }
  const Shape lake{Polygon{shore}, "shore", ""};
  std::vector<Shape> ops{Shape{Rectangle{{0, 0}, {10, 10}}, "outer", ""}, lake};
  for (int k = 0; k < 60; ++k) {
    const Vec2 c{0.8 + 1.2 * (k % 8), 0.8 + 1.2 * (k / 8)};
    if (norm(c - Vec2{5, 5}) > 2.3) ops.push_back(Shape{Circle{c, 0.25}, "hole", ""});
  }
  Problem p;
  p.geometry = Shape{Csg{CsgOp::kDifference, ops}, "", ""};
  DistanceSize graded;
  graded.shape = lake;
  graded.slope = 0.3;
  graded.h_max = 3.0;
  p.size.terms.push_back(graded);
  p.h0 = 0.04;
  const CompiledProblem c = compile_problem(p);
  ASSERT_EQ(std::count_if(c.geometry.code.begin(), c.geometry.code.end(),
                          [](const Instruction& i) { return i.op == Op::kUnionIndexed; }),
            1);
  ASSERT_NE(c.size.shapes.code[0].bvh, kNoBvh);
  expect_engines_agree(c);
}

// Islands with lakes, as an imported coastline has them: the sea in a box minus 12 islands, each
// a square minus 9 lakes, so the islands' union and each island's lakes are indexed unions, one
// inside the other (nests_indexed_unions). The device follows both levels there, as the host
// always does.
TEST(GpuIndexedGeometry, IslandsWithLakesMatchTheCpuEngine) {
  SKIP_WITHOUT_GPU();
  std::vector<Shape> islands;
  for (int i = 0; i < 12; ++i) {
    const Vec2 lo{1.0 + 2.0 * (i % 4), 1.0 + 2.5 * (i / 4)};
    std::vector<Shape> ops{Shape{Rectangle{lo, lo + Vec2{1.2, 1.2}}, "island", ""}};
    for (int k = 0; k < 9; ++k)
      ops.push_back(
          Shape{Circle{lo + Vec2{0.25 + 0.35 * (k % 3), 0.25 + 0.35 * (k / 3)}, 0.1}, "lake", ""});
    islands.push_back(Shape{Csg{CsgOp::kDifference, ops}, "", ""});
  }
  Problem p;
  p.geometry = Shape{Csg{CsgOp::kDifference,
                         {Shape{Rectangle{{0, 0}, {9, 9}}, "outer", ""},
                          Shape{Csg{CsgOp::kUnion, islands}, "", ""}}},
                     "", ""};
  p.h0 = 0.06;
  const CompiledProblem c = compile_problem(p);
  ASSERT_TRUE(nests_indexed_unions(c.geometry));
  expect_engines_agree(c);
}

// Gridded size fields on the device (size_eval.cuh reads the grid that load_problem uploads):
// a 2 x 1 rectangle minus a disk, with a grid term (a smooth bump, 21 x 11 samples, its border
// extended beyond x = 1.6) and a distance term about the disk; then the same field limited by a
// gradation (one grid term over the whole box). The initial points, one step on random points
// and whole meshes agree with the CPU engine's.
CompiledProblem gridded_problem(double gradation) {
  Problem p;
  p.geometry = Shape{Csg{CsgOp::kDifference,
                         {Shape{Rectangle{{0, 0}, {2, 1}}, "outer", ""},
                          Shape{Circle{{1.4, 0.5}, 0.2}, "hole", ""}}},
                     "", ""};
  GridSize grid;
  grid.origin = {0, 0};
  grid.spacing = {0.08, 0.1};
  grid.nx = 21;
  grid.ny = 11;
  for (uint32_t j = 0; j < grid.ny; ++j)
    for (uint32_t i = 0; i < grid.nx; ++i)
      grid.values.push_back(
          static_cast<float>(1.5 + std::sin(3.0 * i * 0.08) * std::cos(2.0 * j * 0.1)));
  p.size.terms.push_back(grid);
  DistanceSize near_hole;
  near_hole.shape = Shape{Circle{{1.4, 0.5}, 0.2}, "hole", ""};
  near_hole.h_min = 0.7;
  near_hole.slope = 3.0;
  near_hole.h_max = 3.0;
  p.size.terms.push_back(near_hole);
  p.size.gradation = gradation;
  p.h0 = 0.04;
  return compile_problem(p);
}

TEST(GpuGridSize, GriddedAndGradedSizeFieldsMatchTheCpuEngine) {
  SKIP_WITHOUT_GPU();
  ThreadPool pool;
  for (const double gradation : {0.0, 0.05}) {
    SCOPED_TRACE("gradation " + std::to_string(gradation));
    const CompiledProblem c = gridded_problem(gradation);
    ASSERT_NE(c.size.terms[0].grid, kNoGrid);
    ASSERT_EQ(c.size.terms.size(), gradation > 0 ? 1u : 2u);
    {
      CpuEngine cpu(pool);
      GpuEngine gpu(0);
      const int64_t n_cpu = cpu.initialize(c), n_gpu = gpu.initialize(c);
      EXPECT_NEAR(n_gpu, n_cpu, std::max<int64_t>(2, n_cpu / 1000));
    }
    {
      const auto pts = random_points(c, 3000, 11);
      CpuEngine cpu(pool);
      GpuEngine gpu(0);
      load_and_triangulate(c, pts, {&cpu, &gpu});
      const StepResult sc = cpu.move_points(), sg = gpu.move_points();
      EXPECT_NEAR(sc.max_move, sg.max_move, 1e-9);
      std::vector<Vec2> a, b;
      cpu.read_points(a);
      gpu.read_points(b);
      ASSERT_EQ(a.size(), b.size());
      EXPECT_LT(point_gaps(c, a, b).interior, 1e-12 * c.h0);
    }
    CpuEngine cpu(pool);
    GpuEngine gpu(0);
    const MeshResult rc = generate_mesh(c, cpu, nullptr, nullptr);
    const MeshResult rg = generate_mesh(c, gpu, nullptr, nullptr);
    expect_meshes_agree(rc, rg);
    EXPECT_GE(rg.quality.q_min, 0.65);
  }
}

TEST(GpuEngine, SameJobTwiceGivesTheSameBitsAndAllocatesNothingNew) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled("G5", 5000);
  GpuEngine gpu(0);
  gpu.warm_up();
  const MeshResult first = generate_mesh(c, gpu, nullptr, nullptr);
  const int64_t allocations = GpuEngine::device_allocations();
  const MeshResult second = generate_mesh(c, gpu, nullptr, nullptr);
  EXPECT_EQ(GpuEngine::device_allocations(), allocations) << "the arena should be warm";
  EXPECT_EQ(first.mesh.points.size(), second.mesh.points.size());
  EXPECT_TRUE(
      std::equal(first.mesh.points.begin(), first.mesh.points.end(), second.mesh.points.begin()));
  EXPECT_EQ(first.mesh.triangles, second.mesh.triangles);
}

// Small triangulations get their bars and CSR from a replayed graph (filter_and_bars), with room
// for three bars a triangle; the same job with every launch direct, and the bars sized first,
// gives the same bits.
TEST(GpuEngine, BarsFromTheReplayedGraphAreTheDirectLaunchesOwn) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = compiled("G5", 5000);
  GpuEngine replayed(0), direct(0);
  direct.set_replayed_triangles(0);
  const MeshResult a = generate_mesh(c, replayed, nullptr, nullptr);
  const MeshResult b = generate_mesh(c, direct, nullptr, nullptr);
  EXPECT_GT(replayed.bars_replays(), 0);
  EXPECT_EQ(direct.bars_replays(), 0);
  ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
  EXPECT_TRUE(std::equal(a.mesh.points.begin(), a.mesh.points.end(), b.mesh.points.begin()));
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.stats.iterations, b.stats.iterations);
}

// Small triangulations (up to 8,192 triangles) get their repairs, and their bars and CSR, from
// one block's launch each (flip_round.h, bars_in_one_block.cu); the same jobs with the kernels
// one by one and the cooperative flip loop give the same bits, on a uniform disk, a domain with
// corners and a graded field.
TEST(GpuEngine, SmallTopologyInOneBlockIsTheKernelsOwn) {
  SKIP_WITHOUT_GPU();
  for (const std::string id : {"G1", "G3", "G5"}) {
    SCOPED_TRACE(id);
    const CompiledProblem c = compiled(id, 2000);
    GpuEngine one_block(0), kernels(0);
    kernels.set_one_block_topology(false);
    const MeshResult a = generate_mesh(c, one_block, nullptr, nullptr);
    const MeshResult b = generate_mesh(c, kernels, nullptr, nullptr);
    EXPECT_EQ(one_block.bars_replays(), 0) << "every triangulation should fit one block";
    EXPECT_GT(kernels.bars_replays(), 0);
    EXPECT_GT(one_block.one_read_retriangulations(), 0);
    EXPECT_EQ(kernels.one_read_retriangulations(), 0);
    ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
    EXPECT_TRUE(std::equal(a.mesh.points.begin(), a.mesh.points.end(), b.mesh.points.begin()));
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    EXPECT_EQ(a.stats.iterations, b.stats.iterations);
    EXPECT_EQ(a.stats.retriangulations, b.stats.retriangulations);
  }
}

// A small job's steps launched behind each retriangulation's repair, before the host reads its
// outcome (retriangulate_and_move: one wait for both), are the steps launched after it, bit for
// bit; the same on a uniform disk, a domain with corners and a graded field, and where one flip
// round a launch leaves most repairs unsettled on the device (the steps then wait for the rest).
TEST(GpuEngine, StepsBehindASmallRepairAreTheStepsAfterIt) {
  SKIP_WITHOUT_GPU();
  int64_t batches_before = 0;  // the last job's with every round a launch allows
  for (const auto& [id, rounds] :
       {std::pair{"G1", 0}, std::pair{"G3", 0}, std::pair{"G5", 0}, std::pair{"G5", 1}}) {
    SCOPED_TRACE(std::string(id) + " rounds " + std::to_string(rounds));
    const CompiledProblem c = compiled(id, 2000);
    GpuEngine behind(0), after(0);
    behind.set_steps_behind_repairs(true);
    after.set_steps_behind_repairs(false);
    for (GpuEngine* e : {&behind, &after})
      if (rounds > 0) e->set_flip_rounds_per_launch(rounds);
    const MeshResult a = generate_mesh(c, behind, nullptr, nullptr);
    const MeshResult b = generate_mesh(c, after, nullptr, nullptr);
    EXPECT_EQ(after.steps_behind_repair_batches(), 0);
    if (rounds == 0) {
      EXPECT_GT(behind.steps_behind_repair_batches(), 0);
    } else {
      // The one-block repair may settle none of them: the steps then all wait (0 batches).
      EXPECT_LT(behind.steps_behind_repair_batches(), batches_before)
          << "one round a launch should leave repairs to the host";
    }
    batches_before = behind.steps_behind_repair_batches();
    ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
    EXPECT_TRUE(std::equal(a.mesh.points.begin(), a.mesh.points.end(), b.mesh.points.begin()));
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
    EXPECT_EQ(a.stats.iterations, b.stats.iterations);
    EXPECT_EQ(a.stats.retriangulations, b.stats.retriangulations);
    EXPECT_EQ(a.stats.flips, b.stats.flips);
  }
}

TEST(GpuEngine, MissingDeviceIsUnavailable) {
  SKIP_WITHOUT_GPU();
  try {
    GpuEngine engine(gpu_device_count());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUnavailable);
  }
}

}  // namespace
}  // namespace meshd
