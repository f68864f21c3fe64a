#include "core/distmesh/refine.h"

#include <gtest/gtest.h>

#include <algorithm>
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

struct Split {
  std::vector<Vec2> points;                         // the coarse mesh's, then the midpoints
  std::vector<std::array<int32_t, 3>> triangles;    // the coarse mesh's
  std::vector<std::array<int32_t, 3>> refined;      // refine_by_midpoints'
  size_t coarse_points = 0;
  size_t coarse_edges = 0;
};

// `p` meshed, then refined for the level of half its h0, as the multilevel loop does.
Split mesh_and_refine(const Problem& p) {
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  generate_mesh(c, engine, nullptr, nullptr);
  Split s;
  engine.read_points(s.points);
  engine.read_triangles(s.triangles);
  s.coarse_points = s.points.size();
  std::map<std::array<int32_t, 2>, int> edges;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k)
      ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  s.coarse_edges = edges.size();
  CompiledProblem finer = c;
  finer.h0 = 0.5 * c.h0;
  s.refined = refine_by_midpoints(finer, s.points, s.triangles);
  return s;
}

// The split triangles are counter-clockwise, cover the coarse mesh's area within `area_share`
// of it, and form a valid triangulation: every directed edge once, its reverse at most once.
void expect_valid_split(const Split& s, double area_share) {
  double before = 0, after = 0;
  for (const auto& t : s.triangles) before += area(s.points, t);
  std::map<std::array<int32_t, 2>, int> directed;
  for (const auto& t : s.refined) {
    ASSERT_GT(orientation_sign(s.points[t[0]], s.points[t[1]], s.points[t[2]]), 0);
    after += area(s.points, t);
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  EXPECT_NEAR(after, before, area_share * before);
  for (const auto& [e, uses] : directed) EXPECT_EQ(uses, 1) << e[0] << "-" << e[1];
}

// A relaxed coarse mesh refined for half its h0: its edges, all near h0 h, are split, so nearly
// every triangle splits in four; boundary midpoints lie on the boundary; the split triangles are
// counter-clockwise, cover (nearly) the same area, and form a valid triangulation.
TEST_P(Refine, SplitsARelaxedMeshInFourOverItsOwnMidpoints) {
  Problem p = testing::benchmark_problem(GetParam(), 0.1);
  p.h0 = h0_for_node_count(p, 1000);
  const Split s = mesh_and_refine(p);
  const size_t midpoints = s.points.size() - s.coarse_points;
  EXPECT_GE(midpoints, 0.97 * static_cast<double>(s.coarse_edges));
  EXPECT_GE(s.refined.size(), 3.9 * static_cast<double>(s.triangles.size()));
  const CompiledProblem c = compile_problem(p);
  for (size_t i = s.coarse_points; i < s.points.size(); ++i)
    EXPECT_LT(eval_sdf(c.geometry.view(), s.points[i]), 1e-3 * c.h0);
  // Projected boundary midpoints bulge the boundary triangles out (or in, along a hole).
  expect_valid_split(s, 0.01);
}

// Fixed nodes closer than the finer level's edge (here 61 along the bottom of a square, a
// third of the coarse edge apart) keep their short edges whole: splitting them would make the
// next level denser along that side than its size field, and each further level four times so.
// The split triangulation stays valid where one or two of a triangle's edges are split.
TEST(Refine, EdgesAlreadyShortEnoughStayWhole) {
  Problem p;
  p.geometry = Shape{Rectangle{{0, 0}, {1, 1}}, "", ""};
  p.h0 = 0.05;
  for (int i = 0; i <= 60; ++i) p.fixed_points.push_back({i / 60.0, 0.0});
  const Split s = mesh_and_refine(p);
  int on_bottom = 0;
  for (size_t i = s.coarse_points; i < s.points.size(); ++i) on_bottom += s.points[i].y < 1e-9;
  EXPECT_EQ(on_bottom, 0);
  EXPECT_GT(s.points.size() - s.coarse_points, 0u);
  expect_valid_split(s, 1e-9);
  std::vector<int> used(s.points.size(), 0);
  for (const auto& t : s.refined)
    for (int32_t v : t) used[v] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

INSTANTIATE_TEST_SUITE_P(Geometries, Refine, ::testing::Values("G1", "G2", "G3", "G4", "G5"));

}  // namespace
}  // namespace meshd
