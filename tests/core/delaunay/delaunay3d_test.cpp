// delaunay_tetrahedralize (delaunay3d.h): positive tetrahedra that fill the hull and are
// Delaunay, the lowest of coinciding points kept, and the same list on one thread and on several
// (CGAL's parallel insertion), for random points and for a lattice whose every cube's corners are
// cospherical.
#include "core/delaunay/delaunay3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "tests/core/random_points3.h"

namespace meshd {
namespace {

double signed_volume(const std::vector<Vec3>& p, const std::array<int32_t, 4>& t) {
  const Vec3 a = p[t[0]];
  return dot(p[t[1]] - a, cross(p[t[2]] - a, p[t[3]] - a)) / 6.0;
}

using testing::random_points3;

std::vector<Vec3> lattice(int cells) {
  std::vector<Vec3> p;
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j)
      for (int k = 0; k <= cells; ++k) p.push_back({1.0 * i, 1.0 * j, 1.0 * k});
  return p;
}

void expect_fills(const std::vector<Vec3>& p, const std::vector<std::array<int32_t, 4>>& tets,
                  double hull_volume) {
  double total = 0.0;
  for (const auto& t : tets) {
    const double v = signed_volume(p, t);
    EXPECT_GT(v, 0.0);
    total += v;
  }
  EXPECT_NEAR(total, hull_volume, 1e-9 * hull_volume);
}

TEST(Delaunay3d, TheSameTetrahedraOnOneThreadAndOnSeveral) {
  const std::vector<Vec3> points = random_points3(30000, 7);
  const auto one = delaunay_tetrahedralize(points, 1);
  const auto four = delaunay_tetrahedralize(points, 4);
  EXPECT_EQ(one, four);
  // Spot-check the empty-sphere property on a sample of tetrahedra against all points.
  for (size_t k = 0; k < one.size(); k += one.size() / 20) {
    const auto& t = one[k];
    // Circumcentre c from |c - a|^2 = |c - b|^2 = ... (three linear equations).
    const Vec3 a = points[t[0]];
    const Vec3 e1 = points[t[1]] - a, e2 = points[t[2]] - a, e3 = points[t[3]] - a;
    const double det = dot(e1, cross(e2, e3));
    const Vec3 c =
        a + (1.0 / (2.0 * det)) * (dot(e1, e1) * cross(e2, e3) + dot(e2, e2) * cross(e3, e1) +
                                   dot(e3, e3) * cross(e1, e2));
    const double r2 = dot(c - a, c - a);
    for (const Vec3& q : points) EXPECT_GE(dot(c - q, c - q), r2 * (1.0 - 1e-9));
  }
}

TEST(Delaunay3d, ACosphericalLatticeTriangulatesTheSameOnAnyThreadCount) {
  const std::vector<Vec3> points = lattice(30);  // 29,791 points, 8 on every cube's sphere
  const auto one = delaunay_tetrahedralize(points, 1);
  EXPECT_EQ(delaunay_tetrahedralize(points, 3), one);
  expect_fills(points, one, 30.0 * 30.0 * 30.0);
  // Each lowest index first, the list sorted.
  for (size_t k = 0; k < one.size(); ++k) {
    EXPECT_LT(one[k][0], one[k][1]);
    EXPECT_LT(one[k][1], one[k][2]);
    EXPECT_LT(one[k][1], one[k][3]);
    if (k > 0) {
      EXPECT_LT(one[k - 1], one[k]);
    }
  }
}

TEST(Delaunay3d, CoincidingPointsLeaveTheLowestIndex) {
  std::vector<Vec3> points = lattice(2);
  const size_t n = points.size();
  points.push_back(points[13]);  // the centre again
  points.push_back(points[0]);
  const auto tets = delaunay_tetrahedralize(points);
  expect_fills(points, tets, 8.0);
  for (const auto& t : tets)
    for (int32_t v : t) EXPECT_LT(v, static_cast<int32_t>(n));
}

TEST(Delaunay3d, MovingAFewPointsGivesTheTetrahedraOfTheirNewPlaces) {
  std::vector<Vec3> points = random_points3(25000, 11);
  Tetrahedralization3 kept;
  kept.build(points, 2);
  std::vector<int32_t> moved;
  for (int32_t i = 7; i < 25000; i += 499) {
    points[i] = points[i] + Vec3{0.01, -0.02, 0.015};
    moved.push_back(i);
  }
  const auto after = kept.move(points, moved);
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(*after, delaunay_tetrahedralize(points, 1));
  // A point moved onto another's place: nothing, and the next build starts afresh.
  points[moved[0]] = points[moved[1] + 1];
  EXPECT_FALSE(kept.move(points, {moved[0]}).has_value());
  EXPECT_EQ(kept.build(points, 1), delaunay_tetrahedralize(points, 1));
}

// The loop's density control takes nodes out and renumbers the rest; the kept triangulation
// must then be the one of the remaining points, numbered as they are, and moves go on from it.
TEST(Delaunay3d, RemovingPointsRenumbersTheRestAsACompactionDoes) {
  std::vector<Vec3> points = random_points3(5000, 12);
  Tetrahedralization3 kept;
  kept.build(points, 1);
  const std::vector<int32_t> gone = {0, 3, 4, 999, 2500, 4999};
  ASSERT_TRUE(kept.remove(gone));
  std::vector<Vec3> rest;
  for (size_t i = 0; i < points.size(); ++i)
    if (!std::binary_search(gone.begin(), gone.end(), static_cast<int32_t>(i)))
      rest.push_back(points[i]);
  const auto after = kept.move(rest, {});
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(*after, delaunay_tetrahedralize(rest, 1));
  rest[10] = rest[10] + Vec3{0.02, 0.01, -0.01};
  const auto moved = kept.move(rest, {10});
  ASSERT_TRUE(moved.has_value());
  EXPECT_EQ(*moved, delaunay_tetrahedralize(rest, 1));
}

// With coinciding points the kept triangulation cannot say which index a vertex stands for.
TEST(Delaunay3d, RemovingFromATriangulationWithDuplicatesStartsAfresh) {
  std::vector<Vec3> points = lattice(2);
  points.push_back(points[13]);
  Tetrahedralization3 kept;
  kept.build(points, 1);
  EXPECT_FALSE(kept.remove({0}));
  points.erase(points.begin());
  EXPECT_FALSE(kept.move(points, {}).has_value());
}

}  // namespace
}  // namespace meshd
