// Corner clusters (corner_clusters.h): of corners closer than a share of the local edge, only the
// sharpest stays fixed; corners farther apart, and the caller's own fixed points, all stay.
#include "core/distmesh/corner_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

using testing::rectangle;

SizeProgram uniform() { return compile_size_field({}); }

// Turns not known: measured around each crowded corner, as at crossings.
std::vector<double> unknown(size_t n) { return std::vector<double>(n, NAN); }

// The unit square with a narrow notch cut into its corner (1, 1): the notch's sides meet at
// (1 - 4e, 1 - 4e) at 16 degrees (a reflex corner of 344 degrees for the domain, 164 from
// straight) and leave the square's sides at (1, 1 - e) and (1 - e, 1) at 53 degrees (127 from
// straight). Its three corners sit within 5e of each other.
Shape square_with_a_notch(double e) {
  return Shape{Polygon{{{0, 0}, {1, 0}, {1, 1 - e}, {1 - 4 * e, 1 - 4 * e}, {1 - e, 1}, {0, 1}}},
               "", ""};
}

TEST(CornerClusters, CornersFarApartAllStay) {
  const Program square = compile_geometry(rectangle({0, 0}, {1, 1}));
  const std::vector<Vec2> corners = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(thin_corner_clusters(corners, unknown(4), {}, square, uniform(), 0.1), corners);
}

TEST(CornerClusters, OfACloseClusterTheSharpestStays) {
  const double e = 0.01;
  const Program notched = compile_geometry(square_with_a_notch(e));
  const std::vector<Vec2> corners = {{0, 0},     {1, 0}, {1, 1 - e}, {1 - 4 * e, 1 - 4 * e},
                                     {1 - e, 1}, {0, 1}};
  const std::vector<Vec2> sharpest = {{0, 0}, {1, 0}, {1 - 4 * e, 1 - 4 * e}, {0, 1}};
  EXPECT_EQ(thin_corner_clusters(corners, unknown(6), {}, notched, uniform(), 0.5), sharpest);
  // The same with the turns the compiler gives.
  std::vector<double> turns;
  const std::vector<Vec2> found = boundary_corners(notched, program_bounds(notched), &turns);
  ASSERT_EQ(found.size(), 6u);
  EXPECT_NEAR(turns[0], std::numbers::pi / 2, 1e-12);  // the square's corner (0, 0)
  EXPECT_EQ(thin_corner_clusters(found, turns, {}, notched, uniform(), 0.5).size(), 4u);
  EXPECT_TRUE(std::find(found.begin(), found.end(), Vec2{1 - 4 * e, 1 - 4 * e}) != found.end());
  // At edges under 1.4 e / kCornerClusterShare (the notch's mouth) every corner is apart enough.
  EXPECT_EQ(
      thin_corner_clusters(corners, unknown(6), {}, notched, uniform(), e / kCornerClusterShare),
      corners);
}

TEST(CornerClusters, TheCallersFixedPointsWinOverCorners) {
  const Program square = compile_geometry(rectangle({0, 0}, {1, 1}));
  const std::vector<Vec2> corners = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> thinned =
      thin_corner_clusters(corners, unknown(4), {{0.99, 0.995}}, square, uniform(), 0.1);
  EXPECT_EQ(thinned, (std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
}

TEST(CornerClusters, TheReachFollowsTheSizeField) {
  // Edges of h0 = 0.1 near x = 0, growing to 8 h0 away from it: two corners 0.05 apart stay at
  // x = 0 (0.05 > 0.25 h0) and become a cluster at x = 1 (h about 0.8 there).
  SizeFieldSpec graded;
  graded.terms.push_back(
      DistanceSize{Shape{HalfPlane{{1, 0}, 0}, "", ""}, /*h_min=*/1, /*slope=*/7, /*h_max=*/8});
  const Program box = compile_geometry(rectangle({0, 0}, {1, 1}));
  const std::vector<Vec2> near_fine = {{0, 0.3}, {0, 0.35}};
  const std::vector<Vec2> near_coarse = {{1, 0.3}, {1, 0.35}};
  const SizeProgram field = compile_size_field(graded);
  EXPECT_EQ(thin_corner_clusters(near_fine, unknown(2), {}, box, field, 0.1).size(), 2u);
  EXPECT_EQ(thin_corner_clusters(near_coarse, unknown(2), {}, box, field, 0.1).size(), 1u);
}

}  // namespace
}  // namespace meshd
