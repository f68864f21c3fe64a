// The 3D GPU engine (gpu_engine3.h) against the CPU engine: the same steps from the same nodes
// and bars (positions to 1e-9 h0, the measures, density control's nodes), over every part of a
// compiled geometry the device copies (primitives, CSG, a 2D profile, a triangle surface, a graded
// size field); whole jobs that agree in size and quality; a domain it cannot evaluate refused.
#include "kernels/gpu_engine3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh3d/cpu_engine3.h"
#include "core/distmesh3d/distmesh3d.h"
#include "core/distmesh3d/generate_mesh3d.h"
#include "core/distmesh3d/geometry_domain3d.h"
#include "core/distmesh3d/initial_points3d.h"
#include "core/distmesh3d/topology3d.h"
#include "core/geometry3d/compile3d.h"
#include "core/mesh3d/tet_validity.h"
#include "kernels/gpu_engine.h"

namespace meshd {
namespace {

#define SKIP_WITHOUT_GPU3() \
  if (gpu_device_count() == 0) GTEST_SKIP() << "no CUDA device visible: GPU tests skipped"

template <typename Node>
Shape3 node(Node n, std::string name = "") {
  return Shape3{std::move(n), std::move(name), ""};
}

// A regular tetrahedron's four faces, turned outward.
Polyhedron small_tetrahedron(Vec3 c, double r) {
  Polyhedron p;
  p.vertices = {c + Vec3{r, r, r}, c + Vec3{r, -r, -r}, c + Vec3{-r, r, -r}, c + Vec3{-r, -r, r}};
  p.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return p;
}

// A disk extruded to a slab, minus a ball and a tetrahedron of triangles: every kind of part
// the device copies.
Shape3 mixed_solid() {
  Shape disk{Circle{{0.0, 0.0}, 1.0}, "disk", ""};
  return node(Csg3{
      CsgOp::kDifference,
      {node(Extrusion{std::move(disk), 0.8}, "slab"), node(Sphere{{0.0, 0.0, 0.8}, 0.4}, "dimple"),
       node(small_tetrahedron({0.4, -0.3, 0.4}, 0.15), "tet")}});
}

SizeField3 graded_towards_origin() {
  SizeField3 f;
  f.terms.push_back(DistanceSize3{node(Sphere{{0.0, 0.0, 0.0}, 0.1}), 1.0, 1.5, 2.5});
  return f;
}

struct Start {
  Nodes3 nodes;
  Topology3 topology;
};

Start start_of(const Domain3& domain, double h0) {
  const Params3 params;
  Start s;
  s.nodes.points = initial_points3d(domain, h0, params.geps, params.seed);
  s.nodes.fixed = static_cast<int64_t>(domain.fixed.size());
  s.nodes.momentum.assign(s.nodes.points.size(), Vec3{});
  // Nudged off the lattice, so that the forces differ from node to node.
  for (size_t i = static_cast<size_t>(s.nodes.fixed); i < s.nodes.points.size(); ++i)
    s.nodes.points[i] = s.nodes.points[i] +
                        0.05 * h0 * Vec3{std::sin(1.0 * i), std::cos(2.0 * i), std::sin(3.0 * i)};
  s.nodes.at_triangulation = s.nodes.points;
  s.topology = triangulate3d(domain, s.nodes.points, s.nodes.fixed, params.geps * h0, 0.0, nullptr);
  return s;
}

// Steps both engines `steps` times from the same start and compares. The L0 scale's sums run in
// another order on the device, so the last bits differ, and each step's projection (a finite
// difference over 1.5e-8 h0) amplifies them: positions agree to about 2e-7 h0 after one step.
void expect_same_steps(const Domain3& domain, double h0, int steps, double tolerance) {
  const Params3 params;
  Start cpu_start = start_of(domain, h0), gpu_start = cpu_start;
  ASSERT_GT(cpu_start.topology.bars.size(), 100u);
  CpuEngine3 cpu(nullptr);
  GpuEngine3 gpu(0);
  cpu.begin(domain, h0, params);
  gpu.begin(domain, h0, params);
  cpu.start(cpu_start.nodes, cpu_start.topology);
  gpu.start(gpu_start.nodes, gpu_start.topology);
  for (int k = 0; k < steps; ++k) {
    const StepResult a = cpu.step(), b = gpu.step();
    EXPECT_NEAR(a.max_move, b.max_move, 1e-6 * a.max_move) << "step " << k;
    EXPECT_NEAR(a.rms_move, b.rms_move, 1e-6 * a.rms_move) << "step " << k;
    EXPECT_NEAR(a.max_drift, b.max_drift, 1e-6 * a.max_drift) << "step " << k;
  }
  EXPECT_EQ(cpu.crowded_nodes(), gpu.crowded_nodes());
  gpu.sync();
  const auto& p = cpu_start.nodes.points;
  const auto& q = gpu_start.nodes.points;
  ASSERT_EQ(p.size(), q.size());
  double worst = 0.0, worst_momentum = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    worst = std::fmax(worst, norm(p[i] - q[i]));
    worst_momentum =
        std::fmax(worst_momentum, norm(cpu_start.nodes.momentum[i] - gpu_start.nodes.momentum[i]));
  }
  EXPECT_LT(worst, tolerance * h0) << "after " << steps << " steps";
  EXPECT_LT(worst_momentum, tolerance * h0) << "after " << steps << " steps";
  // A second sync without a step changes nothing on the host.
  const double moved = gpu_start.nodes.points[0].x += 1.0;
  gpu.sync();
  EXPECT_EQ(gpu_start.nodes.points[0].x, moved);
}

TEST(GpuEngine3, StepsTheBallAsTheCpuDoes) {
  SKIP_WITHOUT_GPU3();
  const GeometryDomain3 ball(node(Sphere{{0, 0, 0}, 1.0}), 0.15);
  expect_same_steps(ball.domain(), 0.15, 1, 1e-6);
  expect_same_steps(ball.domain(), 0.15, 5, 1e-5);
}

TEST(GpuEngine3, StepsEveryPartOfACompiledGeometryAndAGradedField) {
  SKIP_WITHOUT_GPU3();
  const SizeField3 size = graded_towards_origin();
  const GeometryDomain3 solid(std::make_shared<const Program3>(compile_geometry3(mixed_solid())),
                              0.08, compile_size_field3(size, 1.0), false, true,
                              kExactDistanceEdges * 0.08 * 2.5);
  ASSERT_NE(solid.domain().size_field, nullptr);
  ASSERT_FALSE(solid.domain().fixed.empty());
  expect_same_steps(solid.domain(), 0.08, 1, 1e-6);
  expect_same_steps(solid.domain(), 0.08, 5, 1e-5);
}

TEST(GpuEngine3, FindsTheCrowdedNodesTheCpuFinds) {
  SKIP_WITHOUT_GPU3();
  const GeometryDomain3 ball(node(Sphere{{0, 0, 0}, 1.0}), 0.15);
  const Domain3& domain = ball.domain();
  const Params3 params;
  Start a = start_of(domain, 0.15);
  // Squeeze a few free nodes onto their neighbours.
  for (size_t i = 10; i < a.nodes.points.size(); i += 97)
    a.nodes.points[i] = a.nodes.points[i - 1] + Vec3{1e-3, 0, 0};
  a.nodes.at_triangulation = a.nodes.points;
  a.topology =
      triangulate3d(domain, a.nodes.points, a.nodes.fixed, params.geps * 0.15, 0.0, nullptr);
  Start b = a;
  CpuEngine3 cpu(nullptr);
  GpuEngine3 gpu(0);
  cpu.begin(domain, 0.15, params);
  gpu.begin(domain, 0.15, params);
  cpu.start(a.nodes, a.topology);
  gpu.start(b.nodes, b.topology);
  cpu.step();
  gpu.step();
  const std::vector<int32_t> crowded = cpu.crowded_nodes();
  EXPECT_FALSE(crowded.empty());
  EXPECT_EQ(gpu.crowded_nodes(), crowded);
}

// Whole jobs: the two engines' meshes are both valid and of the same size and quality (their
// last bits differ, the GPU repairs triangulations that the host builds, and the loop's decisions
// follow them, so the meshes are not identical).
TEST(GpuEngine3, MeshesAsTheCpuEngineDoes) {
  SKIP_WITHOUT_GPU3();
  Problem3 problem;
  problem.geometry = mixed_solid();
  problem.size = graded_towards_origin();
  problem.h0 = 0.07;
  ThreadPool pool(2);
  GpuEngine3 gpu(0);
  const MeshResult3 a = generate_mesh3d(problem, &pool, nullptr, nullptr);
  const MeshResult3 b = generate_mesh3d(problem, &pool, nullptr, nullptr, &gpu);
  for (const MeshResult3* r : {&a, &b}) {
    EXPECT_TRUE(r->stats.converged);
    const TetValidityReport v = check_tet_validity(r->mesh);
    EXPECT_TRUE(v.valid()) << (v.problems.empty() ? "" : v.problems[0]);
    EXPECT_GE(r->quality.min_dihedral_deg, 10.0);
    EXPECT_GE(r->quality.q_min, 0.2);
    EXPECT_LT(r->quality.max_surface_offset, 1e-3 * problem.h0);
  }
  // The GPU repaired triangulations by flips; the CPU engine builds them on the host.
  EXPECT_GT(b.stats.repaired_retriangulations, 0);
  EXPECT_EQ(a.stats.repaired_retriangulations, 0);
  const double na = static_cast<double>(a.mesh.points.size());
  EXPECT_NEAR(static_cast<double>(b.mesh.points.size()), na, 0.02 * na);
  // Not worse (the repaired triangulations lead elsewhere: on the host's flips this job ends
  // at q_mean 0.843 against the builds' 0.831).
  EXPECT_GE(b.quality.q_mean, a.quality.q_mean - 0.01);
  EXPECT_NEAR(b.quality.volume, a.quality.volume, 0.005 * a.quality.volume);
}

// A snapshot brings the nodes to the host between two steps; the job goes on as without it.
TEST(GpuEngine3, SnapshotsChangeNothing) {
  SKIP_WITHOUT_GPU3();
  struct EveryThird : Observer {
    bool wants_snapshot(int iteration) override { return iteration % 3 == 0; }
    void on_volume_snapshot(int, const std::vector<Vec3>& points,
                            const std::vector<std::array<int32_t, 4>>*) override {
      ++snapshots;
      moved = moved || (!last.empty() && points != last);
      last = points;
    }
    int snapshots = 0;
    bool moved = false;  // the nodes a snapshot saw were those of the latest step
    std::vector<Vec3> last;
  } observer;
  const GeometryDomain3 ball(node(Sphere{{0, 0, 0}, 1.0}), 0.15);
  GpuEngine3 gpu(0);
  const Params3 params;
  const Relaxed3 plain = distmesh3d(ball.domain(), 0.15, params, nullptr, nullptr, nullptr, &gpu);
  const Relaxed3 watched =
      distmesh3d(ball.domain(), 0.15, params, nullptr, &observer, nullptr, &gpu);
  EXPECT_GT(observer.snapshots, 2);
  EXPECT_TRUE(observer.moved);
  EXPECT_EQ(plain.iterations, watched.iterations);
  EXPECT_TRUE(plain.points == watched.points);
  EXPECT_TRUE(plain.tets == watched.tets);
}

TEST(GpuEngine3, RefusesADomainWithoutACompiledGeometry) {
  SKIP_WITHOUT_GPU3();
  Domain3 domain;
  domain.distance = [](Vec3 p) { return norm(p) - 1.0; };
  GpuEngine3 gpu(0);
  const Params3 params;
  try {
    gpu.begin(domain, 0.1, params);
    FAIL() << "begin accepted a domain of callables";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
  }
}

}  // namespace
}  // namespace meshd
