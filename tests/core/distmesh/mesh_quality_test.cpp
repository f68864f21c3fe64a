// The whole pipeline (compile_problem, CpuEngine, generate_mesh) on the benchmark geometries
// G1-G5 of geometries.md at about 2,000 nodes, held to what "a good mesh" means there; and the
// loop's contract: determinism, the iteration cap, cancellation, the observer, the clean-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/quality.h"
#include "core/mesh/validity.h"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/core/distmesh/forwarding_engine.h"

namespace meshd {
namespace {

constexpr double kTwoOverSqrt3 = 1.1547005383792515;

struct MeshRun {
  CompiledProblem compiled;  // the engine and the mesh refer to it
  MeshResult result;
};

// Meshes benchmark `id` aimed at `nodes` nodes; `edit` may change the problem first.
template <typename Edit>
MeshRun mesh(const std::string& id, double nodes, Edit edit, Observer* observer = nullptr,
             const std::atomic<bool>* cancel = nullptr, unsigned threads = 0) {
  Problem p = testing::benchmark_problem(id, 1.0);
  p.h0 = h0_for_node_count(p, nodes);
  edit(p);
  MeshRun run;
  run.compiled = compile_problem(p);
  ThreadPool pool(threads);
  CpuEngine engine(pool);
  run.result = generate_mesh(run.compiled, engine, observer, cancel);
  return run;
}
MeshRun mesh(const std::string& id, double nodes) {
  return mesh(id, nodes, [](Problem&) {});
}

// N = (2 / sqrt(3)) * integral of 1 / (h0 h)^2 dA (geometries.md). For G5, h = min(4r - 1, 2):
// the ring 0.5 < r < 0.75 gives pi (ln 2 + 1/2) / 8, the rest (4 - pi 0.75^2) / 4
// (node_estimate_test checks this closed form against a quadrature).
double expected_nodes(const std::string& id, double h0) {
  const double integral = id == "G5" ? M_PI * (std::log(2.0) + 0.5) / 8 + (4 - M_PI * 0.5625) / 4
                                     : testing::benchmark_area(id);
  return kTwoOverSqrt3 * integral / (h0 * h0);
}

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

// ---- G1-G5 --------------------------------------------------------------------------------------

class BenchmarkMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(BenchmarkMesh, MeetsTheTargetsOfGeometriesMd) {
  const std::string id = GetParam();
  const MeshRun run = mesh(id, 2000);
  const Mesh& m = run.result.mesh;
  const CompiledProblem& c = run.compiled;
  const double h0 = c.h0;
  const QualityStats& q = run.result.quality;
  const RunStats& s = run.result.stats;
  std::printf(
      "[ measured ] %s: h0 %.5f, nodes %zu (expected %.0f), triangles %zu, q_min %.4f, "
      "q_mean %.4f, min angle %.1f deg, iterations %d, retriangulations %d, converged %d, "
      "cleanup removed %lld, %.3f s\n",
      id.c_str(), h0, m.points.size(), expected_nodes(id, h0), m.triangles.size(), q.q_min,
      q.q_mean, q.min_angle_deg, s.iterations, s.retriangulations, s.converged,
      static_cast<long long>(s.cleanup_removed), s.t_total);

  // A valid mesh: oriented, conforming, every node used, boundary edges and tags consistent.
  const ValidityReport report = check_validity(m);
  EXPECT_TRUE(report.valid()) << join(report.problems);

  // Area within 0.5% (curved boundaries are chords).
  EXPECT_NEAR(mesh_area(m) / testing::benchmark_area(id), 1.0, 0.005);

  // Boundary nodes on the boundary, within 1e-3 h0.
  double worst_boundary = 0;
  for (const auto& e : m.boundary_edges)
    for (int32_t v : e)
      worst_boundary =
          std::max(worst_boundary, std::fabs(eval_sdf(c.geometry.view(), m.points[v])));
  EXPECT_LE(worst_boundary, 1e-3 * h0);

  // Fixed points (corners, polygon vertices) are nodes, bitwise.
  for (Vec2 f : c.fixed_points) {
    const bool present =
        std::any_of(m.points.begin(), m.points.end(), [&](Vec2 p) { return p == f; });
    EXPECT_TRUE(present) << "fixed point (" << f.x << ", " << f.y << ") is not a node";
  }
  const size_t want_fixed = id == "G2" || id == "G5" ? 4 : id == "G3" ? 10 : 0;
  EXPECT_EQ(c.fixed_points.size(), want_fixed);

  // Node count within 10% of the equilateral estimate.
  EXPECT_NEAR(static_cast<double>(m.points.size()) / expected_nodes(id, h0), 1.0, 0.10);

  // Quality: DistMesh's mean and a worst element of a frontal mesher.
  EXPECT_GE(q.q_min, 0.65);
  EXPECT_GE(q.q_mean, id == "G5" ? 0.96 : 0.97);
  // The reported statistics are those of the returned mesh.
  const std::vector<double> tq = triangle_quality(m);
  ASSERT_FALSE(tq.empty());
  EXPECT_DOUBLE_EQ(q.q_min, *std::min_element(tq.begin(), tq.end()));
  EXPECT_TRUE(s.converged);

  // Boundary groups: named as in benchmark_geometries, every edge tagged with its own boundary.
  const bool holed = id == "G2" || id == "G5";
  const std::vector<std::string> want_names =
      holed ? std::vector<std::string>{"outer", "hole"} : std::vector<std::string>{"outer"};
  EXPECT_EQ(m.boundary_names, want_names);
  ASSERT_EQ(m.boundary_tags.size(), m.boundary_edges.size());
  int64_t hole_edges = 0, wrong = 0;
  for (size_t i = 0; i < m.boundary_edges.size(); ++i) {
    const std::string& name = m.boundary_names.at(m.boundary_tags[i]);
    const Vec2 a = m.points[m.boundary_edges[i][0]], b = m.points[m.boundary_edges[i][1]];
    if (holed) {
      const bool on_hole =
          std::fabs(norm(a) - 0.5) <= 1e-3 * h0 && std::fabs(norm(b) - 0.5) <= 1e-3 * h0;
      auto on_square = [&](Vec2 p) {
        return std::fabs(std::max(std::fabs(p.x), std::fabs(p.y)) - 1) <= 1e-3 * h0;
      };
      const bool ok = on_hole ? name == "hole" : (name == "outer" && on_square(a) && on_square(b));
      hole_edges += on_hole;
      if (!ok && ++wrong <= 5)
        ADD_FAILURE() << "edge (" << a.x << ", " << a.y << ") - (" << b.x << ", " << b.y
                      << ") tagged " << name;
    } else if (name != "outer") {
      ++wrong;
    }
  }
  EXPECT_EQ(wrong, 0);
  // The hole's circumference over the edge length near it (h = 1 there): about pi / h0 edges.
  if (holed) {
    EXPECT_NEAR(static_cast<double>(hole_edges), M_PI / h0, 0.15 * M_PI / h0);
  }
}

INSTANTIATE_TEST_SUITE_P(Geometries, BenchmarkMesh, ::testing::Values("G1", "G2", "G3", "G4", "G5"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

// ---- The loop's contract ------------------------------------------------------------------------

bool same_mesh(const Mesh& a, const Mesh& b) {
  return a.points.size() == b.points.size() &&
         std::equal(a.points.begin(), a.points.end(), b.points.begin(),
                    [](Vec2 p, Vec2 q) { return p == q; }) &&
         a.triangles == b.triangles && a.boundary_edges == b.boundary_edges &&
         a.boundary_tags == b.boundary_tags && a.boundary_names == b.boundary_names;
}

TEST(GenerateMesh, DeterministicForASeedAndDifferentForAnother) {
  auto seed5 = [](Problem& p) { p.seed = 5; };
  const MeshRun a = mesh("G5", 600, seed5, nullptr, nullptr, 2);
  // Other allocations in between, as in a service between two jobs, and other thread counts.
  std::vector<std::vector<char>> heap_noise;
  for (int i = 0; i < 5000; ++i) heap_noise.emplace_back(1000 + 37 * i);
  for (unsigned threads : {2u, 1u, 4u}) {
    const MeshRun b = mesh("G5", 600, seed5, nullptr, nullptr, threads);
    EXPECT_TRUE(same_mesh(a.result.mesh, b.result.mesh)) << threads << " threads";
    EXPECT_EQ(a.result.stats.iterations, b.result.stats.iterations);
  }
  const MeshRun other = mesh("G5", 600, [](Problem& p) { p.seed = 6; });
  EXPECT_FALSE(same_mesh(a.result.mesh, other.result.mesh));
  // The other seed's mesh is a good mesh too.
  EXPECT_TRUE(check_validity(other.result.mesh).valid());
  EXPECT_GE(other.result.quality.q_min, 0.65);
}

// Edge = h0 * h(p) whatever the field's scale: a uniform 0.5 halves the edges (4x the nodes),
// and a graded field scaled by 0.5 gives the nodes of the unscaled one at h0 / 2.
TEST(GenerateMesh, SizeFieldScaleIsPartOfTheEdgeLength) {
  const MeshRun plain = mesh("G1", 1000);
  const MeshRun halved = mesh("G1", 250, [](Problem& p) {
    p.size.terms.resize(1);  // a default term is a uniform one
    std::get<UniformSize>(p.size.terms[0]).value = 0.5;
  });
  EXPECT_NEAR(static_cast<double>(halved.result.mesh.points.size()),
              static_cast<double>(plain.result.mesh.points.size()), 0.05 * 1000);
  EXPECT_NEAR(halved.compiled.h0, plain.compiled.h0, 1e-12);

  const MeshRun g5 = mesh("G5", 1000);
  const MeshRun g5_scaled = mesh("G5", 250, [](Problem& p) {
    for (auto& term : p.size.terms) {
      std::visit(
          [](auto& t) {
            if constexpr (std::is_same_v<std::decay_t<decltype(t)>, DistanceSize>) {
              t.h_min *= 0.5;
              t.slope *= 0.5;
              t.h_max *= 0.5;
            } else if constexpr (std::is_same_v<std::decay_t<decltype(t)>, UniformSize>) {
              t.value *= 0.5;
            } else if constexpr (std::is_same_v<std::decay_t<decltype(t)>, GridSize>) {
              t.scale *= 0.5;
            } else {  // a feature-size term: twice the elements across
              t.elements *= 2;
              t.h_min *= 0.5;
              t.h_max *= 0.5;
            }
          },
          term);
    }
  });
  EXPECT_NEAR(static_cast<double>(g5_scaled.result.mesh.points.size()),
              static_cast<double>(g5.result.mesh.points.size()), 0.05 * 1000);
  EXPECT_NEAR(static_cast<double>(g5_scaled.result.mesh.points.size()),
              estimate_node_count(g5_scaled.compiled), 0.1 * 1000);
}

TEST(GenerateMesh, IterationCapStopsUnconvergedWithAValidMesh) {
  const MeshRun run = mesh("G2", 600, [](Problem& p) { p.params.max_iterations = 5; });
  EXPECT_FALSE(run.result.stats.converged);
  EXPECT_EQ(run.result.stats.iterations, 5);
  const ValidityReport report = check_validity(run.result.mesh);
  EXPECT_TRUE(report.valid()) << join(report.problems);
  EXPECT_GT(run.result.mesh.triangles.size(), 100u);
}

class CancelAt : public Observer {
 public:
  CancelAt(int iteration, std::atomic<bool>& flag) : iteration_(iteration), flag_(flag) {}
  void on_progress(const Progress& p) override {
    last_ = p.iteration;
    if (p.iteration == iteration_) flag_ = true;
  }
  int last_ = 0;

 private:
  int iteration_;
  std::atomic<bool>& flag_;
};

TEST(GenerateMesh, CancellationThrowsWithinOneIteration) {
  std::atomic<bool> cancel{false};
  CancelAt observer(3, cancel);
  try {
    mesh(
        "G1", 600, [](Problem&) {}, &observer, &cancel);
    FAIL() << "generate_mesh returned after cancellation";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kCancelled) << e.what();
  }
  EXPECT_EQ(observer.last_, 3);
  // Set before the start: no iteration runs.
  std::atomic<bool> already{true};
  CancelAt none(1000, already);
  EXPECT_THROW(mesh(
                   "G1", 600, [](Problem&) {}, &none, &already),
               Error);
  EXPECT_EQ(none.last_, 0);
}

class Recorder : public Observer {
 public:
  void on_progress(const Progress& p) override { progress.push_back(p); }
  bool wants_snapshot(int iteration) override {
    asked.push_back(iteration);
    return iteration % 10 == 1;
  }
  void on_snapshot(int iteration, const std::vector<Vec2>& points,
                   const std::vector<std::array<int32_t, 3>>* triangles) override {
    snapshot_iterations.push_back(iteration);
    snapshot_nodes.push_back(points.size());
    with_triangles.push_back(triangles != nullptr);
    if (triangles != nullptr) {
      for (const auto& t : *triangles)
        for (int32_t v : t)
          if (v < 0 || static_cast<size_t>(v) >= points.size()) ++bad_indices;
    }
  }
  std::vector<Progress> progress;
  std::vector<int> asked, snapshot_iterations;
  std::vector<size_t> snapshot_nodes;
  std::vector<bool> with_triangles;
  int bad_indices = 0;
};

void expect_observed_run(const Recorder& r, const RunStats& stats) {
  ASSERT_FALSE(r.progress.empty());
  EXPECT_EQ(r.progress.front().iteration, 1);
  for (size_t i = 1; i < r.progress.size(); ++i) {
    EXPECT_GT(r.progress[i].iteration, r.progress[i - 1].iteration) << "progress " << i;
    EXPECT_GE(r.progress[i].retriangulations, r.progress[i - 1].retriangulations);
    EXPECT_GE(r.progress[i].elapsed_s, r.progress[i - 1].elapsed_s);
  }
  for (const Progress& p : r.progress) {
    EXPECT_GT(p.nodes, 0);
    EXPECT_GE(p.max_move, 0.0);
  }
  // The main loop's last step passed the termination test.
  EXPECT_GE(r.progress.size(), static_cast<size_t>(stats.iterations));
  // One snapshot for each iteration that asked for one, in order; the first carries triangles.
  std::vector<int> want;
  for (int it : r.asked)
    if (it % 10 == 1) want.push_back(it);
  EXPECT_EQ(r.snapshot_iterations, want);
  ASSERT_FALSE(r.with_triangles.empty());
  EXPECT_TRUE(r.with_triangles.front());
  EXPECT_EQ(r.bad_indices, 0);
  for (size_t i = 0; i < r.snapshot_iterations.size(); ++i) {
    // The snapshot's points are as many as the progress of that iteration reported.
    for (const Progress& p : r.progress)
      if (p.iteration == r.snapshot_iterations[i]) {
        EXPECT_EQ(static_cast<int64_t>(r.snapshot_nodes[i]), p.nodes);
        break;
      }
  }
}

TEST(GenerateMesh, ObserverGetsProgressAndSnapshotsItAskedFor) {
  Recorder r;
  const MeshRun run = mesh(
      "G1", 600, [](Problem& p) { p.params.cleanup = false; }, &r);
  expect_observed_run(r, run.result.stats);
  EXPECT_EQ(r.progress.back().iteration, run.result.stats.iterations);
  EXPECT_EQ(static_cast<int>(r.progress.size()), run.result.stats.iterations);
  // Topology changes between snapshots at this size: some later snapshots carry triangles too.
  EXPECT_GT(std::count(r.with_triangles.begin(), r.with_triangles.end(), true), 1);
}

// The clean-up relaxes again after removing nodes; its iterations must continue the count, or a
// client streaming progress would see time run backwards (G3 at 300 nodes exercises it).
TEST(GenerateMesh, ProgressIterationsKeepIncreasingThroughTheCleanup) {
  Recorder r;
  const MeshRun run = mesh(
      "G3", 300, [](Problem&) {}, &r);
  ASSERT_GT(run.result.stats.cleanup_removed, 0) << "the case should exercise the clean-up";
  for (size_t i = 1; i < r.progress.size(); ++i) {
    ASSERT_GT(r.progress[i].iteration, r.progress[i - 1].iteration)
        << "progress " << i << " of " << r.progress.size()
        << " (main loop: " << run.result.stats.iterations << " iterations)";
  }
}

// The CPU engine asked for its steps in batches, as the loop asks the GPU engine (engine.h).
class BatchingEngine final : public testing::ForwardingEngine {
 public:
  using ForwardingEngine::ForwardingEngine;
  void move_points_until(const StepRule& rule, int first_iteration, int limit,
                         std::vector<StepResult>& steps) override {
    if (limit > 1) ++batches;
    Engine::move_points_until(rule, first_iteration, limit, steps);
  }
  int preferred_batch() const override { return 7; }

  int batches = 0;  // calls for more than one step
};

// Batches of steps must run exactly the loop of one step at a time: the same iterations,
// triangulations, density control and clean-up, the same mesh, and the same progress and
// snapshots, each iteration asked about once and in order.
TEST(GenerateMesh, BatchesOfStepsRunTheSameLoop) {
  for (const auto& [id, nodes] : {std::pair<std::string, double>{"G1", 600}, {"G3", 300}}) {
    Problem p = testing::benchmark_problem(id, 1.0);
    p.h0 = h0_for_node_count(p, nodes);
    const CompiledProblem c = compile_problem(p);
    ThreadPool pool;
    CpuEngine one(pool);
    BatchingEngine batched(pool);
    Recorder r_one, r_batched;
    const MeshResult a = generate_mesh(c, one, &r_one, nullptr);
    const MeshResult b = generate_mesh(c, batched, &r_batched, nullptr);
    EXPECT_GT(batched.batches, 10) << id;
    EXPECT_EQ(a.stats.iterations, b.stats.iterations) << id;
    EXPECT_EQ(a.stats.cleanup_iterations, b.stats.cleanup_iterations) << id;
    EXPECT_EQ(a.stats.retriangulations, b.stats.retriangulations) << id;
    EXPECT_EQ(a.stats.density_removed, b.stats.density_removed) << id;
    EXPECT_EQ(a.stats.cleanup_removed, b.stats.cleanup_removed) << id;
    EXPECT_EQ(a.mesh.points, b.mesh.points) << id;
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles) << id;
    expect_observed_run(r_batched, b.stats);
    ASSERT_EQ(r_one.progress.size(), r_batched.progress.size()) << id;
    for (size_t i = 0; i < r_one.progress.size(); ++i) {
      EXPECT_EQ(r_one.progress[i].iteration, r_batched.progress[i].iteration) << id << " " << i;
      EXPECT_EQ(r_one.progress[i].max_move, r_batched.progress[i].max_move) << id << " " << i;
      EXPECT_EQ(r_one.progress[i].nodes, r_batched.progress[i].nodes) << id << " " << i;
    }
    // Asked about the same iterations, in order; a batch asks ahead, so the last batch may have
    // asked about iterations that never ran.
    ASSERT_GE(r_batched.asked.size(), r_one.asked.size()) << id;
    EXPECT_TRUE(std::equal(r_one.asked.begin(), r_one.asked.end(), r_batched.asked.begin())) << id;
    for (size_t i = r_one.asked.size(); i < r_batched.asked.size(); ++i)
      EXPECT_GT(r_batched.asked[i], r_one.progress.back().iteration) << id;
    EXPECT_EQ(r_one.snapshot_iterations, r_batched.snapshot_iterations) << id;
    EXPECT_EQ(r_one.with_triangles, r_batched.with_triangles) << id;
  }
}

// A node that never stops moving (here: every step reports an interior move of at least 50
// dptol, as a node cycling between two triangulations does) must not hold the loop to
// max_iterations: once the largest move of the settled steps (rms under dptol) stops setting
// new lows for 100 of them (the patience, step_rule.cuh), the relaxation is over.
class CyclingNodeEngine final : public testing::ForwardingEngine {
 public:
  using ForwardingEngine::ForwardingEngine;
  StepResult move_points() override {
    StepResult r = cpu_.move_points();
    r.max_move = std::max(r.max_move, 0.05);
    steps.push_back(r);
    return r;
  }
  std::vector<StepResult> steps;
};

TEST(GenerateMesh, ANodeThatNeverStopsDoesNotHoldTheLoopToMaxIterations) {
  Problem p = testing::benchmark_problem("G2", 1.0);
  p.h0 = h0_for_node_count(p, 1500);
  p.params.multilevel = Params::Multilevel::kOff;
  p.params.cleanup = false;
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CyclingNodeEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  EXPECT_TRUE(r.stats.converged);
  EXPECT_LT(r.stats.iterations, 2000);
  // It ended at the 100th settled step after the last new low of the largest move.
  const double dptol = c.params.dptol;
  double lowest = INFINITY;
  int stalled = 0;
  for (const StepResult& s : engine.steps) {
    if (!(s.rms_move < dptol)) continue;
    stalled = s.max_move < lowest ? 0 : stalled + 1;
    lowest = std::min(lowest, s.max_move);
  }
  EXPECT_TRUE(engine.steps.back().rms_move < dptol);
  EXPECT_EQ(stalled, 100);
  EXPECT_TRUE(check_validity(r.mesh).valid());
}

TEST(GenerateMesh, CleanupImprovesTheWorstElementOnG3) {
  const MeshRun on = mesh("G3", 2000);
  const MeshRun off = mesh("G3", 2000, [](Problem& p) { p.params.cleanup = false; });
  std::printf("[ measured ] G3 clean-up on: q_min %.4f q_mean %.4f; off: q_min %.4f q_mean %.4f\n",
              on.result.quality.q_min, on.result.quality.q_mean, off.result.quality.q_min,
              off.result.quality.q_mean);
  EXPECT_GE(on.result.quality.q_min, off.result.quality.q_min);
  EXPECT_GE(on.result.quality.q_mean, off.result.quality.q_mean - 0.002);
  EXPECT_TRUE(check_validity(off.result.mesh).valid());
  EXPECT_EQ(off.result.stats.cleanup_removed, 0);
  EXPECT_EQ(off.result.stats.optimized_moves, 0);
}

}  // namespace
}  // namespace meshd
