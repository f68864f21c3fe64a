// optimize_worst_elements: the clean-up's last step may move nodes, but never leaves a triangle
// flatter than it found it.
#include "core/distmesh/optimize_worst.h"

#include <gtest/gtest.h>

#include "core/common/thread_pool.h"
#include "core/distmesh/assemble_mesh.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/mesh/boundary.h"
#include "core/mesh/validity.h"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

// UTM-sized coordinates, where a flat triangle's round-off is far above 1e-16 of its size.
Vec2 at(double x, double y) { return Vec2{6.0e5, 6.6e6} + 100.0 * Vec2{x, y}; }

// A node of the mesh's boundary that lies inside the domain is snapped onto the boundary. When
// the opposite edge of its triangle already lies there, the snap flattens that triangle to
// round-off, and its sign is the round-off's: some of these positions would come out with a
// positive area far below any real triangle's, which no later move can undo.
TEST(OptimizeWorst, SnappingANodeOntoTheBoundaryNeverFlattensItsTriangle) {
  Problem p;
  p.h0 = 100.0;
  p.auto_corners = false;
  p.geometry = Shape{Polygon{{at(0, 0), at(3, 1), at(0, 3)}}, "", ""};
  const CompiledProblem problem = compile_problem(p);
  const std::vector<std::array<int32_t, 3>> triangles = {{0, 1, 2}};
  for (int k = 0; k < 64; ++k) {
    // a and b on the slanted side, v inside just above it, between them.
    const Vec2 a = at(0.3, 0.1), b = at(2.7, 0.9);
    const double s = 0.2 + 0.6 * k / 63.0;
    const Vec2 v = a + s * (b - a) + 100.0 * Vec2{-0.01, 0.03};
    std::vector<Vec2> points = {a, b, v};
    optimize_worst_elements(problem, points, triangles, boundary_half_edges(triangles));
    const Mesh mesh = assemble_mesh(problem, points, triangles, boundary_half_edges(triangles));
    const ValidityReport report = check_validity(mesh);
    EXPECT_TRUE(report.valid()) << "v at s = " << s << ": " << report.problems.front();
  }
}

// A mesh early in its relaxation, with many triangles under the threshold.
MeshCopy early_mesh(const std::string& id) {
  const CompiledProblem problem = compile_problem(testing::benchmark_problem(id, 0.05));
  ThreadPool pool(0);
  CpuEngine engine(pool);
  engine.initialize(problem);
  engine.retriangulate(true);
  for (int k = 0; k < 5; ++k) engine.move_points();
  engine.retriangulate(false);
  MeshCopy copy;
  engine.read_mesh(copy);
  return copy;
}

// The GPU engine hands the optimisation the triangles under the threshold, found on the device:
// starting from them must give the bits that measuring every triangle gives.
TEST(OptimizeWorst, StartingFromTheTrianglesBelowTheThresholdMovesTheSameNodes) {
  for (const std::string id : {"G1", "G2", "G5"}) {
    const CompiledProblem problem = compile_problem(testing::benchmark_problem(id, 0.05));
    const MeshCopy copy = early_mesh(id);
    std::vector<int32_t> below;
    for (size_t t = 0; t < copy.triangles.size(); ++t) {
      const auto& tri = copy.triangles[t];
      if (oriented_radius_ratio(copy.points[tri[0]], copy.points[tri[1]], copy.points[tri[2]]) <
          kOptimizeBelowQuality)
        below.push_back(static_cast<int32_t>(t));
    }
    ASSERT_GT(below.size(), 10u) << id;
    std::vector<Vec2> measured = copy.points, seeded = copy.points;
    const int64_t a =
        optimize_worst_elements(problem, measured, copy.triangles, copy.boundary, nullptr);
    const int64_t b =
        optimize_worst_elements(problem, seeded, copy.triangles, copy.boundary, &below);
    EXPECT_GT(a, 0) << id;
    EXPECT_EQ(a, b) << id;
    for (size_t i = 0; i < measured.size(); ++i) {
      ASSERT_EQ(measured[i].x, seeded[i].x) << id << ", node " << i;
      ASSERT_EQ(measured[i].y, seeded[i].y) << id << ", node " << i;
    }
  }
}

// Nodes that share no triangle move at once on the pool's threads: the same moves for any number
// of threads, and every triangle still turns left.
TEST(OptimizeWorst, TheSameMovesOnAnyNumberOfThreads) {
  for (const std::string id : {"G2", "G5"}) {
    const CompiledProblem problem = compile_problem(testing::benchmark_problem(id, 0.05));
    const MeshCopy copy = early_mesh(id);
    std::vector<Vec2> alone = copy.points;
    const int64_t a = optimize_worst_elements(problem, alone, copy.triangles, copy.boundary);
    EXPECT_GT(a, 0) << id;
    for (unsigned threads : {2u, 5u}) {
      ThreadPool pool(threads);
      std::vector<Vec2> pooled = copy.points;
      const int64_t b =
          optimize_worst_elements(problem, pooled, copy.triangles, copy.boundary, nullptr, &pool);
      EXPECT_EQ(a, b) << id << ", " << threads << " threads";
      for (size_t i = 0; i < alone.size(); ++i) {
        ASSERT_EQ(alone[i].x, pooled[i].x) << id << ", node " << i;
        ASSERT_EQ(alone[i].y, pooled[i].y) << id << ", node " << i;
      }
    }
    for (const auto& t : copy.triangles)
      EXPECT_GT(oriented_radius_ratio(alone[t[0]], alone[t[1]], alone[t[2]]), 0.0) << id;
  }
}

// A triangle above the threshold until the snap puts its sagging corner onto the boundary, where
// it falls under it (q 0.91, then 0.74): it must be optimised as if every triangle were measured.
TEST(OptimizeWorst, StartingFromTheTrianglesBelowAlsoMeasuresAroundSnappedNodes) {
  Problem p;
  p.h0 = 1.0;
  p.auto_corners = false;
  p.geometry = Shape{Polygon{{{0, 0}, {2, 0}, {2, 10}, {0, 10}}}, "", ""};
  const CompiledProblem problem = compile_problem(p);
  const std::vector<std::array<int32_t, 3>> triangles = {{0, 1, 2}};
  const std::vector<Vec2> start = {{0, 0}, {2, 0}, {0.7, 1.2}};
  ASSERT_GE(oriented_radius_ratio(start[0], start[1], start[2]), kOptimizeBelowQuality);
  const std::vector<int32_t> boundary = boundary_half_edges(triangles), below;
  std::vector<Vec2> measured = start, seeded = start;
  const int64_t a = optimize_worst_elements(problem, measured, triangles, boundary, nullptr);
  const int64_t b = optimize_worst_elements(problem, seeded, triangles, boundary, &below);
  EXPECT_GT(a, 1);  // the snap, then the optimisation
  EXPECT_EQ(a, b);
  for (size_t i = 0; i < start.size(); ++i) {
    EXPECT_EQ(measured[i].x, seeded[i].x) << "node " << i;
    EXPECT_EQ(measured[i].y, seeded[i].y) << "node " << i;
  }
}

}  // namespace
}  // namespace meshd
