#include "core/distmesh/refine.h"

#include <gtest/gtest.h>

#include <map>

#include "core/common/thread_pool.h"
#include "core/delaunay/exact_predicates.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

double area(const std::vector<Vec2>& p, const std::array<int32_t, 3>& t) {
  const Vec2 u = p[t[1]] - p[t[0]], v = p[t[2]] - p[t[0]];
  return 0.5 * (u.x * v.y - u.y * v.x);
}

class Refine : public ::testing::TestWithParam<std::string> {};

// A relaxed coarse mesh split in four: one new point per edge, boundary midpoints on the
// boundary, four counter-clockwise triangles per triangle over (nearly) the same area, and every
// interior edge of the split shared by exactly two of its triangles.
TEST_P(Refine, SplitsEveryTriangleInFourOverItsOwnMidpoints) {
  Problem p = testing::benchmark_problem(GetParam(), 0.1);
  p.h0 = h0_for_node_count(p, 1000);
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  generate_mesh(c, engine, nullptr, nullptr);
  std::vector<Vec2> points;
  std::vector<std::array<int32_t, 3>> triangles;
  engine.read_points(points);
  engine.read_triangles(triangles);
  const size_t n = points.size();
  const auto refined = refine_by_midpoints(c, points, triangles);

  ASSERT_EQ(refined.size(), 4 * triangles.size());
  std::map<std::array<int32_t, 2>, int> edge_uses;
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k)
      ++edge_uses[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  }
  EXPECT_EQ(points.size(), n + edge_uses.size());
  for (size_t i = n; i < points.size(); ++i)
    EXPECT_LT(eval_sdf(c.geometry.view(), points[i]), 1e-3 * c.h0);
  double before = 0, after = 0;
  for (const auto& t : triangles) before += area(points, t);
  std::map<std::array<int32_t, 2>, int> directed;
  for (const auto& t : refined) {
    ASSERT_GT(orientation_sign(points[t[0]], points[t[1]], points[t[2]]), 0);
    after += area(points, t);
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  // Projected boundary midpoints bulge the boundary triangles out (or in, along a hole).
  EXPECT_NEAR(after, before, 0.01 * before);
  // A valid triangulation: every directed edge once, and its reverse at most once.
  for (const auto& [e, uses] : directed) EXPECT_EQ(uses, 1) << e[0] << "-" << e[1];
}

INSTANTIATE_TEST_SUITE_P(Geometries, Refine, ::testing::Values("G1", "G2", "G3", "G4", "G5"));

}  // namespace
}  // namespace meshd
