// Folds (a node moved across an edge since the triangulation was made) cut out and filled again:
// the result is a triangulation of the hull, and Lawson's flips take it to the one CGAL builds.
#include "core/delaunay/refill_folds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/lawson_repair.h"
#include "core/delaunay/triangle_neighbors.h"
#include "tests/core/delaunay/fold_fixtures.h"

namespace meshd {
namespace {

using testing::jittered_lattice;
using testing::push_across;

// Triangles as sets: each rotated to start at its smallest index, then sorted.
std::vector<std::array<int32_t, 3>> canonical(std::vector<std::array<int32_t, 3>> triangles) {
  for (auto& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// Checks `done` against the triangulation CGAL builds, after flipping it to Delaunay.
void expect_refilled_to_delaunay(const std::vector<Vec2>& points, Triangulation done) {
  ASSERT_FALSE(done.triangles.empty()) << "the fill failed";
  for (const auto& v : done.triangles)
    ASSERT_GT(orientation_sign(points[v[0]], points[v[1]], points[v[2]]), 0);
  std::vector<std::array<int32_t, 3>> links;
  ASSERT_TRUE(triangle_neighbors(done.triangles, points.size(), links));
  EXPECT_EQ(links, done.neighbors);
  const std::vector<char> keep(done.triangles.size(), 1), none(points.size(), 0);
  ASSERT_TRUE(lawson_repair(points, keep, none, done).ok);
  EXPECT_EQ(canonical(done.triangles), canonical(delaunay_triangulate(points).triangles));
}

TEST(RefillFolds, ANodePushedAcrossAnEdgeIsMendedWithoutARebuild) {
  std::vector<Vec2> points = jittered_lattice(30, 3);
  const Triangulation before = delaunay_triangulate(points);
  ASSERT_TRUE(push_across(before, 15 * 30 + 14, points));
  Triangulation flipped = before;
  const std::vector<char> keep(before.triangles.size(), 1), none(points.size(), 0);
  ASSERT_FALSE(lawson_repair(points, keep, none, flipped).ok) << "the move made no fold";
  expect_refilled_to_delaunay(points, refill_folds(points, before, 0));
}

TEST(RefillFolds, ManyFoldsAtOnceNextToEachOtherAndToTheHull) {
  for (uint32_t seed = 0; seed < 10; ++seed) {
    std::vector<Vec2> points = jittered_lattice(40, seed);
    const Triangulation before = delaunay_triangulate(points);
    std::mt19937 rng(seed);
    // Some next to each other (merged holes), some one row in from the hull.
    for (int i = 0; i < 8; ++i)
      push_across(before, static_cast<int32_t>(rng() % points.size()), points);
    push_across(before, 1 * 40 + 20, points);
    push_across(before, 1 * 40 + 21, points);
    SCOPED_TRACE("seed " + std::to_string(seed));
    Triangulation flipped = before;
    const std::vector<char> keep(before.triangles.size(), 1), none(points.size(), 0);
    ASSERT_FALSE(lawson_repair(points, keep, none, flipped).ok) << "the moves made no fold";
    expect_refilled_to_delaunay(points, refill_folds(points, before, 0));
  }
}

TEST(RefillFolds, CuttingAFoldLeavesRightTurningTrianglesWithTheirLinks) {
  std::vector<Vec2> points = jittered_lattice(20, 4);
  Triangulation tri = delaunay_triangulate(points);
  const int32_t pushed = 10 * 20 + 9;
  ASSERT_TRUE(push_across(tri, pushed, points));
  const size_t before = tri.triangles.size();
  ASSERT_TRUE(cut_folds(points, tri));
  EXPECT_LT(tri.triangles.size(), before);
  for (const auto& v : tri.triangles) {
    ASSERT_GT(orientation_sign(points[v[0]], points[v[1]], points[v[2]]), 0);
    EXPECT_TRUE(v[0] != pushed && v[1] != pushed && v[2] != pushed);
  }
  std::vector<std::array<int32_t, 3>> links;
  ASSERT_TRUE(triangle_neighbors(tri.triangles, points.size(), links));
  EXPECT_EQ(links, tri.neighbors);
  EXPECT_FALSE(cut_folds(points, tri)) << "a second cut found another fold";
}

TEST(RefillFolds, NothingToRefillWithoutAFold) {
  std::vector<Vec2> points = jittered_lattice(10, 1);
  const Triangulation tri = delaunay_triangulate(points);
  points[55].x += 0.01;  // moved, but no triangle turned over
  EXPECT_TRUE(refill_folds(points, tri, 0).triangles.empty());
}

}  // namespace
}  // namespace meshd
