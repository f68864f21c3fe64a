#include "core/geometry3d/crease_features3.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry3d/bounds3.h"
#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/sharp_features3.h"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

using testing::csg3;
using testing::cuboid;
using testing::cylinder;
using testing::sphere;

std::vector<Vec3> creases(const Shape3& shape, double spacing) {
  const Program3 program = compile_geometry3(shape);
  return crease_features3(program, domain_bounds3(program), spacing,
                          sharp_features3(program, spacing));
}

TEST(CreaseFeatures3, ABoreThroughAPlateLeavesTwoRimsOfPoints) {
  // The plate [-1, 1]^2 x [0, 0.5] minus a cylinder of radius 0.4 along z through it.
  const Shape3 part =
      csg3(CsgOp::kDifference, {cuboid({-1, -1, 0}, {1, 1, 0.5}), cylinder({0, 0, -1}, 0.4, 2.0)});
  const double spacing = 0.1;
  const std::vector<Vec3> points = creases(part, spacing);
  int top = 0, bottom = 0;
  for (Vec3 p : points) {
    EXPECT_NEAR(std::hypot(p.x, p.y), 0.4, 1e-9);
    const bool on_top = std::fabs(p.z - 0.5) < 1e-9, on_bottom = std::fabs(p.z) < 1e-9;
    EXPECT_TRUE(on_top || on_bottom) << p.z;
    top += on_top;
    bottom += on_bottom;
  }
  // A rim is 2.5 long: between 0.8 and about 2 spacings apart.
  for (int rim : {top, bottom}) {
    EXPECT_GE(rim, 12);
    EXPECT_LE(rim, 32);
  }
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      EXPECT_GE(norm(points[i] - points[j]), kCreaseGapFraction * spacing - 1e-12);
}

TEST(CreaseFeatures3, FlushFacesAndTangentContactMakeNoEdge) {
  // Two boxes side by side: their top faces continue each other.
  EXPECT_TRUE(
      creases(csg3(CsgOp::kUnion, {cuboid({0, 0, 0}, {1, 1, 1}), cuboid({1, 0, 0}, {2, 1, 1})}),
              0.1)
          .empty());
  // A ball inside a box, off its faces: nothing meets.
  EXPECT_TRUE(
      creases(csg3(CsgOp::kDifference, {cuboid({-1, -1, -1}, {1, 1, 1}), sphere({0, 0, 0}, 0.5)}),
              0.1)
          .empty());
}

TEST(CreaseFeatures3, TheSamePointsEveryTime) {
  const Shape3 part =
      csg3(CsgOp::kUnion, {cuboid({-1, -1, -1}, {1, 1, 1}), sphere({1, 0, 0}, 0.6)});
  const std::vector<Vec3> a = creases(part, 0.1), b = creases(part, 0.1);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i] == b[i]);
  // On the circle where the ball meets the face x = 1: radius sqrt(0.6^2 - 0) = 0.6.
  for (Vec3 p : a) {
    EXPECT_NEAR(p.x, 1.0, 1e-9);
    EXPECT_NEAR(std::hypot(p.y, p.z), 0.6, 1e-9);
  }
}

}  // namespace
}  // namespace meshd
