// sharp_features3: a cuboid's corners and edges, a cylinder's rims, a cone's apex, features that
// CSG removes or buries, transforms, and the limits.
#include "core/geometry3d/sharp_features3.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/common/error.h"
#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

using testing::csg3;
using testing::cuboid;
using testing::cylinder;
using testing::frustum;
using testing::sphere;
using testing::transformed3;

std::vector<Vec3> features(const Shape3& s, double spacing) {
  return sharp_features3(compile_geometry3(s), spacing);
}

int count_if(const std::vector<Vec3>& points, bool (*pred)(Vec3)) {
  return static_cast<int>(std::count_if(points.begin(), points.end(), pred));
}

// On the unit cube's edges: at least two coordinates are 0 or 1.
bool on_unit_cube_edge(Vec3 p) {
  auto at = [](double v) { return v == 0.0 || v == 1.0; };
  return int(at(p.x)) + int(at(p.y)) + int(at(p.z)) >= 2;
}
bool is_unit_cube_corner(Vec3 p) {
  auto at = [](double v) { return v == 0.0 || v == 1.0; };
  return at(p.x) && at(p.y) && at(p.z);
}

// The largest distance from a point on the segment a-b to the nearest of `points`, given that
// the points on it are sorted by their parameter: the largest gap between neighbours, halved.
double largest_gap_along(Vec3 a, Vec3 b, const std::vector<Vec3>& points) {
  std::vector<double> t;
  const Vec3 e = b - a;
  for (Vec3 p : points) {
    const double s = dot(p - a, e) / dot(e, e);
    if (s >= -1e-12 && s <= 1 + 1e-12 && norm(p - (a + s * e)) <= 1e-12) t.push_back(s);
  }
  std::sort(t.begin(), t.end());
  double gap = 0;
  for (size_t i = 1; i < t.size(); ++i) gap = std::max(gap, (t[i] - t[i - 1]) * norm(e));
  EXPECT_NEAR(t.front(), 0, 1e-12);
  EXPECT_NEAR(t.back(), 1, 1e-12);
  return gap;
}

TEST(SharpFeatures3, CuboidCornersAndEdges) {
  const Shape3 box = cuboid({0, 0, 0}, {1, 1, 1});
  // 1 / 0.25 = 4 intervals per edge: 8 corners and 3 inner points on each of 12 edges.
  const std::vector<Vec3> f = features(box, 0.25);
  EXPECT_EQ(f.size(), 8u + 12u * 3u);
  EXPECT_EQ(count_if(f, is_unit_cube_corner), 8);
  EXPECT_EQ(count_if(f, on_unit_cube_edge), int(f.size()));
  // A spacing that does not divide the edge: ceil(1 / 0.3) = 4 intervals, 0.25 apart.
  const std::vector<Vec3> g = features(box, 0.3);
  EXPECT_EQ(g.size(), 44u);
  EXPECT_LE(largest_gap_along({0, 0, 0}, {1, 0, 0}, g), 0.3);
  EXPECT_LE(largest_gap_along({1, 1, 0}, {1, 1, 1}, g), 0.3);
  // A spacing longer than the edges leaves the corners alone.
  EXPECT_EQ(features(box, 5).size(), 8u);
}

TEST(SharpFeatures3, CylinderRims) {
  const std::vector<Vec3> f = features(cylinder({0, 0, 0}, 1, 2), 0.1);
  const size_t per_rim = size_t(std::ceil(2 * std::numbers::pi / 0.1));
  EXPECT_EQ(f.size(), 2 * per_rim);
  for (Vec3 p : f) {
    EXPECT_NEAR(std::hypot(p.x, p.y), 1, 1e-14);
    EXPECT_TRUE(std::fabs(p.z) < 1e-14 || std::fabs(p.z - 2) < 1e-14);
  }
  // Neighbours on a rim are at most the spacing apart.
  const double chord = 2 * std::sin(std::numbers::pi / double(per_rim));
  EXPECT_LE(chord, 0.1);
  // A rim smaller than the spacing still gets three points.
  EXPECT_EQ(features(cylinder({0, 0, 0}, 0.01, 2), 0.1).size(), 6u);
}

TEST(SharpFeatures3, ConeApexAndFrustumRims) {
  const std::vector<Vec3> cone = features(frustum({0, 0, 0}, 1, 0, 2), 0.5);
  const size_t per_rim = size_t(std::ceil(2 * std::numbers::pi / 0.5));
  ASSERT_EQ(cone.size(), per_rim + 1);
  EXPECT_EQ(std::count(cone.begin(), cone.end(), Vec3{0, 0, 2}), 1);  // the apex
  const std::vector<Vec3> both = features(frustum({0, 0, 0}, 1, 0.5, 2), 0.5);
  EXPECT_EQ(both.size(), per_rim + size_t(std::ceil(std::numbers::pi / 0.5)));
}

TEST(SharpFeatures3, CuboidMinusASphereKeepsOnlyWhatRemains) {
  // The ball of radius 0.5 about the corner (1, 1, 1) eats that corner and, on each of its three
  // edges (samples 0.2 apart), the samples 0.2 and 0.4 from it: 1 + 3 * 2 of the 8 + 12 * 4.
  const Vec3 c{1, 1, 1};
  const Shape3 bitten = csg3(CsgOp::kDifference, {cuboid({0, 0, 0}, c), sphere(c, 0.5)});
  const Program3 p = compile_geometry3(bitten);
  const std::vector<Vec3> f = sharp_features3(p, 0.2);
  EXPECT_EQ(f.size(), 8u + 12u * 4u - 7u);
  for (Vec3 q : f) {
    EXPECT_TRUE(on_unit_cube_edge(q));
    EXPECT_GT(norm(q - c), 0.5);
    EXPECT_NEAR(eval_sdf3(p.view(), q), 0, 1e-12);
  }
}

TEST(SharpFeatures3, BuriedEdgesDropOut) {
  // Two overlapping cubes: the parts of each one's edges inside the other are not boundary.
  const Shape3 two =
      csg3(CsgOp::kUnion, {cuboid({0, 0, 0}, {1, 1, 1}), cuboid({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5})});
  const Program3 p = compile_geometry3(two);
  const std::vector<Vec3> f = sharp_features3(p, 0.25);
  EXPECT_LT(f.size(), 2u * 44u);
  for (Vec3 q : f) EXPECT_NEAR(eval_sdf3(p.view(), q), 0, 1e-12);
  EXPECT_EQ(std::count(f.begin(), f.end(), Vec3{1, 1, 1}), 0);  // inside the second cube
  EXPECT_EQ(std::count(f.begin(), f.end(), Vec3{0, 0, 0}), 1);
  // A corner shared by two cubes side by side is one point.
  const Shape3 pair =
      csg3(CsgOp::kUnion, {cuboid({0, 0, 0}, {1, 1, 1}), cuboid({1, 0, 0}, {2, 1, 1})});
  const std::vector<Vec3> g = features(pair, 1);
  EXPECT_EQ(std::count(g.begin(), g.end(), Vec3{1, 0, 0}), 1);
  EXPECT_EQ(g.size(), 12u);
}

TEST(SharpFeatures3, TransformedCuboidFeaturesLieOnItsBoundary) {
  const Shape3 turned =
      transformed3(cuboid({0, 0, 0}, {1, 2, 3}), {1.5, {1, 2, 3}, 0.7, {10, -20, 30}});
  const Program3 p = compile_geometry3(turned);
  // Edges 1.5, 3 and 4.5 long (lengths that rounding could not push across an interval count):
  // 4, 8 and 12 intervals, four edges each.
  const std::vector<Vec3> f = sharp_features3(p, 0.4);
  EXPECT_EQ(f.size(), 8u + 4u * (3u + 7u + 11u));
  for (Vec3 q : f) EXPECT_NEAR(eval_sdf3(p.view(), q), 0, 1e-12);
}

TEST(SharpFeatures3, SmoothShapesHaveNone) {
  EXPECT_TRUE(features(sphere({0, 0, 0}, 1), 0.1).empty());
  EXPECT_TRUE(features(testing::torus({0, 0, 0}, 2, 1), 0.1).empty());
}

TEST(SharpFeatures3, Limits) {
  EXPECT_THROW(features(cuboid({0, 0, 0}, {1, 1, 1}), 0), Error);
  try {
    features(csg3(CsgOp::kUnion, {sphere({0, 0, 0}, 1), cuboid({0, 0, 0}, {1, 1, 1}, "", "g.big")}),
             1e-7);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "g.big");
  }
}

}  // namespace
}  // namespace meshd
