// Whole CPU-engine meshes of domains given as distance grids: the unit disk sampled on a grid
// (the segmented-image case with an exact distance), a grid with a disk cut out of it, and a
// disk cut by the grid's border. Held to what the analytic disk (G1) is held to in
// mesh_quality_test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/quality.h"
#include "core/mesh/validity.h"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

constexpr double kPi = std::numbers::pi;

struct GridMesh {
  CompiledProblem compiled;
  MeshResult result;
};

GridMesh mesh(Shape shape, double nodes) {
  Problem p;
  p.geometry = std::move(shape);
  p.h0 = 1.0;
  p.h0 = h0_for_node_count(p, nodes);
  GridMesh run;
  run.compiled = compile_problem(p);
  ThreadPool pool(0);
  CpuEngine engine(pool);
  run.result = generate_mesh(run.compiled, engine, nullptr, nullptr);
  return run;
}

double worst_boundary_distance(const GridMesh& run) {
  double worst = 0;
  for (const auto& e : run.result.mesh.boundary_edges)
    for (int32_t v : e)
      worst = std::max(
          worst, std::fabs(eval_sdf(run.compiled.geometry.view(), run.result.mesh.points[v])));
  return worst;
}

TEST(DistanceGridMesh, DiskFromAGridMeshesLikeTheDisk) {
  // 121 x 121 samples over [-1.5, 1.5]^2: h = 0.025, half the mesh's edge.
  const GridMesh run = mesh(testing::disk_grid(121, "outer"), 2000);
  const Mesh& m = run.result.mesh;
  const double h0 = run.compiled.h0;
  const QualityStats& q = run.result.quality;
  std::printf(
      "[ measured ] grid disk: h0 %.5f, nodes %zu, q_min %.4f, q_mean %.4f, "
      "iterations %d\n",
      h0, m.points.size(), q.q_min, q.q_mean, run.result.stats.iterations);

  const ValidityReport report = check_validity(m);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems.front());
  EXPECT_TRUE(run.compiled.fixed_points.empty());  // a smooth outline: no corners
  // On the grid's zero level set, and that within the interpolation error of the circle.
  EXPECT_LE(worst_boundary_distance(run), 1e-3 * h0);
  for (const auto& e : m.boundary_edges)
    for (int32_t v : e) EXPECT_NEAR(norm(m.points[v]), 1.0, 0.025 * 0.025);
  // Area within 0.5% of the disk's (chords and the interpolation both take a little).
  EXPECT_NEAR(mesh_area(m) / kPi, 1.0, 0.005);
  EXPECT_GE(q.q_min, 0.65);
  EXPECT_GE(q.q_mean, 0.97);
  EXPECT_TRUE(run.result.stats.converged);
  EXPECT_EQ(m.boundary_names, std::vector<std::string>{"outer"});
}

TEST(DistanceGridMesh, GridCombinedWithAnExactHoleKeepsBothBoundaries) {
  // A negative-everywhere grid is its box: a square with a circular hole, like G2, whose four
  // corners come from the grid's box.
  Shape square = testing::distance_grid([](Vec2) { return -1.0; }, {-1, -1}, 0.5, 5, 5, "outer");
  const GridMesh run = mesh(
      testing::csg(CsgOp::kDifference, {std::move(square), testing::circle({0, 0}, 0.5, "hole")}),
      1500);
  const Mesh& m = run.result.mesh;
  EXPECT_TRUE(check_validity(m).valid());
  EXPECT_EQ(run.compiled.fixed_points.size(), 4u);
  EXPECT_LE(worst_boundary_distance(run), 1e-3 * run.compiled.h0);
  EXPECT_NEAR(mesh_area(m) / (4 - kPi * 0.25), 1.0, 0.005);
  EXPECT_GE(run.result.quality.q_min, 0.65);
  EXPECT_EQ(m.boundary_names, (std::vector<std::string>{"outer", "hole"}));
}

TEST(DistanceGridMesh, MaskCutByItsBorderKeepsItsCorners) {
  // A disk cut by the grid's bottom side, as a segmented object touches its image's border: the
  // two corners where the circle meets the side are nodes, and stay sharp.
  const GridMesh run = mesh(testing::distance_grid([](Vec2 p) { return norm(p) - 1.0; },
                                                   {-1.52, 0.0}, 0.025, 123, 61, "outer"),
                            1500);
  const Mesh& m = run.result.mesh;
  EXPECT_TRUE(check_validity(m).valid());
  ASSERT_EQ(run.compiled.fixed_points.size(), 2u);
  for (Vec2 f : run.compiled.fixed_points) {
    EXPECT_NEAR(std::fabs(f.x), 1.0, 1e-9);
    EXPECT_NEAR(f.y, 0.0, 1e-9);
    EXPECT_TRUE(std::find(m.points.begin(), m.points.end(), f) != m.points.end());
  }
  EXPECT_LE(worst_boundary_distance(run), 1e-3 * run.compiled.h0);
  EXPECT_NEAR(mesh_area(m) / (kPi / 2), 1.0, 0.005);
  EXPECT_GE(run.result.quality.q_min, 0.65);
}

}  // namespace
}  // namespace meshd
