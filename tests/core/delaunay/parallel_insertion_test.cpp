// The insertion's Delaunay builder run on the host (parallel_insertion.h), against CGAL: the same
// triangles where the Delaunay triangulation is unique (points in general position), and a valid,
// locally Delaunay triangulation of the convex hull under exact predicates everywhere (grids of
// co-circular points, clusters, duplicates, collinear runs, far-off coordinates). The exact
// orientation it locates points with, against CGAL's.
#include "core/delaunay/parallel_insertion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "core/delaunay/exact_orientation.cuh"
#include "core/delaunay/exact_predicates.h"
#include "tests/core/delaunay/delaunay_checks.h"

namespace meshd {
namespace {

using testing::clustered_points;
using testing::expect_delaunay;
using testing::triangle_set;
using testing::triangle_set_by_position;
using testing::uniform_points;

TEST(ExactOrientation, AgreesWithCgalOnNearlyCollinearPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int collinear = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 60) - 30);
    const Vec2 a{u(rng) * scale + 1e6, u(rng) * scale}, b{u(rng) * scale + 1e6, u(rng) * scale};
    // A point on the line through a and b, rounded, then nudged by a few units in the last place.
    const double s = u(rng) * 3.0;
    Vec2 c{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
    for (int nudge = static_cast<int>(rng() % 5); nudge > 0; --nudge)
      c.x = std::nextafter(c.x, (rng() & 1) ? 1e300 : -1e300);
    if (trial % 7 == 0) c = a;
    const int want = orientation_sign(a, b, c);
    collinear += want == 0;
    ASSERT_EQ(orientation_exact(a, b, c), want) << trial;
    ASSERT_EQ(orientation_exact(b, c, a), want) << trial;
  }
  EXPECT_GT(collinear, 2000);  // the exact stage was exercised
}

TEST(ParallelInsertion, SameTrianglesAsCgalInGeneralPosition) {
  for (int n : {3, 10, 100, 5000}) {
    for (uint32_t seed = 1; seed <= 3; ++seed) {
      const std::vector<Vec2> p = uniform_points(n, seed);
      InsertionStats stats;
      const Triangulation t = insertion_triangulate(p, &stats);
      expect_delaunay(p, t);
      EXPECT_EQ(triangle_set(t), triangle_set(delaunay_triangulate(p))) << n << " " << seed;
      EXPECT_FALSE(stats.fell_back);
      if (n >= 5000) {
        EXPECT_LT(stats.insertion_steps, 60) << "too many steps for " << n;
        EXPECT_GT(stats.flips, 0);
      }
    }
  }
}

TEST(ParallelInsertion, GridsOfCoCircularPoints) {
  for (int side : {2, 7, 40}) {
    std::vector<Vec2> p;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) p.push_back({0.25 * i, 0.25 * j});
    std::shuffle(p.begin(), p.end(), std::mt19937(side));
    InsertionStats stats;
    const Triangulation t = insertion_triangulate(p, &stats);
    expect_delaunay(p, t);
    EXPECT_EQ(static_cast<int>(t.triangles.size()), 2 * (side - 1) * (side - 1));
  }
  // A triangular lattice, as DistMesh starts from, with every row on a line.
  std::vector<Vec2> p;
  for (int r = 0; r < 30; ++r)
    for (int i = 0; i < 30; ++i) p.push_back({i + 0.5 * (r % 2), r * std::sqrt(3.0) / 2});
  expect_delaunay(p, insertion_triangulate(p));
}

TEST(ParallelInsertion, ClustersDuplicatesAndFarOffCoordinates) {
  std::mt19937 rng(11);
  const std::vector<Vec2> clusters = clustered_points(20, 200, 11);
  const Triangulation tc = insertion_triangulate(clusters);
  expect_delaunay(clusters, tc);
  EXPECT_EQ(triangle_set(tc), triangle_set(delaunay_triangulate(clusters)));

  std::vector<Vec2> dup = uniform_points(2000, 5);
  for (int k = 0; k < 600; ++k) dup.push_back(dup[rng() % 2000]);
  std::shuffle(dup.begin(), dup.end(), rng);
  InsertionStats stats;
  const Triangulation td = insertion_triangulate(dup, &stats);
  EXPECT_EQ(stats.duplicates, static_cast<int64_t>(dup.size() - distinct_points(dup).size()));
  EXPECT_GT(stats.duplicates, 0);
  expect_delaunay(dup, td);
  EXPECT_EQ(triangle_set(td), triangle_set_by_position(dup, delaunay_triangulate(dup)));

  // UTM-like coordinates: a few kilometres of points six thousand kilometres from the origin.
  std::vector<Vec2> far = uniform_points(3000, 9);
  for (Vec2& q : far) q = {512000.0 + 3000.0 * q.x, 6663000.0 + 3000.0 * q.y};
  const Triangulation tf = insertion_triangulate(far);
  expect_delaunay(far, tf);
  EXPECT_EQ(triangle_set(tf), triangle_set(delaunay_triangulate(far)));
}

TEST(ParallelInsertion, DegenerateSets) {
  EXPECT_TRUE(insertion_triangulate({}).triangles.empty());
  EXPECT_TRUE(insertion_triangulate({{1, 1}, {1, 1}}).triangles.empty());
  std::vector<Vec2> line;
  for (int i = 0; i < 50; ++i) line.push_back({0.5 * i, 0.25 * i});
  EXPECT_TRUE(insertion_triangulate(line).triangles.empty());
  // Collinear runs on the hull and through the middle, points on the enclosing box's diagonal.
  std::vector<Vec2> p = line;
  p.push_back({0.0, 5.0});
  p.push_back({20.0, 0.0});
  for (int i = 1; i < 20; ++i) p.push_back({static_cast<double>(i), 0.0});
  const Triangulation t = insertion_triangulate(p);
  expect_delaunay(p, t);
}

}  // namespace
}  // namespace meshd
