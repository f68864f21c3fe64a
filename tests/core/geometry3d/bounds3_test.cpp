// program_bounds3 and domain_bounds3: exact boxes of rotated primitives, CSG, half-spaces, and
// the errors for unbounded and empty domains.
#include "core/geometry3d/bounds3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

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
using testing::half_space;
using testing::sphere;
using testing::torus;
using testing::transformed3;

constexpr double kPi = std::numbers::pi;

void expect_box(const Box3& b, Vec3 lo, Vec3 hi, double tol = 1e-12) {
  EXPECT_NEAR(b.min.x, lo.x, tol);
  EXPECT_NEAR(b.min.y, lo.y, tol);
  EXPECT_NEAR(b.min.z, lo.z, tol);
  EXPECT_NEAR(b.max.x, hi.x, tol);
  EXPECT_NEAR(b.max.y, hi.y, tol);
  EXPECT_NEAR(b.max.z, hi.z, tol);
}

Box3 bounds(const Shape3& s) { return domain_bounds3(compile_geometry3(s)); }

TEST(Bounds3, PrimitivesAlone) {
  expect_box(bounds(sphere({1, 2, 3}, 2)), {-1, 0, 1}, {3, 4, 5});
  expect_box(bounds(cuboid({0, 1, 2}, {3, 4, 5})), {0, 1, 2}, {3, 4, 5});
  expect_box(bounds(cylinder({0, 0, 1}, 2, 3)), {-2, -2, 1}, {2, 2, 4});
  expect_box(bounds(frustum({0, 0, 0}, 2, 1, 3)), {-2, -2, 0}, {2, 2, 3});
  expect_box(bounds(torus({0, 0, 0}, 2, 0.5)), {-2.5, -2.5, -0.5}, {2.5, 2.5, 0.5});
}

TEST(Bounds3, RotatedPrimitivesGetTheirExactBoxes) {
  // A unit cube turned 45 degrees about z: its box is sqrt(2) wide.
  const double s = std::sqrt(0.5);
  expect_box(bounds(transformed3(cuboid({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}),
                                 {1, {0, 0, 1}, kPi / 4, {}})),
             {-s, -s, -0.5}, {s, s, 0.5});
  // A cylinder lying along x.
  expect_box(bounds(transformed3(cylinder({0, 0, 0}, 1, 4), {1, {0, 1, 0}, kPi / 2, {}})),
             {0, -1, -1}, {4, 1, 1});
  // A torus standing in the xz plane, scaled by 2.
  expect_box(bounds(transformed3(torus({0, 0, 0}, 2, 0.5), {2, {1, 0, 0}, kPi / 2, {}})),
             {-5, -1, -5}, {5, 1, 5});
}

TEST(Bounds3, CsgCombinesBoxes) {
  const Shape3 a = cuboid({0, 0, 0}, {2, 2, 2}), b = cuboid({1, 1, 1}, {3, 4, 5});
  expect_box(bounds(csg3(CsgOp::kUnion, {a, b})), {0, 0, 0}, {3, 4, 5});
  expect_box(bounds(csg3(CsgOp::kIntersection, {a, b})), {1, 1, 1}, {2, 2, 2});
  expect_box(bounds(csg3(CsgOp::kDifference, {a, b})), {0, 0, 0}, {2, 2, 2});
  // Axis-aligned half-spaces cut a box on their side; six of them make one.
  expect_box(bounds(csg3(CsgOp::kIntersection, {a, half_space({0, 0, 1}, 0.5)})), {0, 0, 0},
             {2, 2, 0.5});
  expect_box(
      bounds(csg3(CsgOp::kIntersection, {half_space({1, 0, 0}, 1), half_space({-1, 0, 0}, 1),
                                         half_space({0, 2, 0}, 4), half_space({0, -1, 0}, 0),
                                         half_space({0, 0, 1}, 3), half_space({0, 0, -1}, -1)})),
      {-1, 0, 1}, {1, 2, 3});
  // A tilted half-space leaves the cube's box as it is.
  expect_box(bounds(csg3(CsgOp::kIntersection, {a, half_space({1, 1, 1}, 1)})), {0, 0, 0},
             {2, 2, 2});
}

std::string error_field(const Shape3& s) {
  try {
    bounds(s);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return e.field();
  }
  return "(no error)";
}

TEST(Bounds3, UnboundedAndEmptyDomainsAreErrors) {
  // The half-space that nothing cuts off is named.
  EXPECT_EQ(error_field(csg3(
                CsgOp::kUnion,
                {sphere({0, 0, 0}, 1, "", "g.u[0]"), half_space({1, 1, 0}, 0, "g.u[1]")}, "g")),
            "g.u[1]");
  // One cut off by an intersection is not blamed for a later one.
  EXPECT_EQ(error_field(csg3(CsgOp::kUnion,
                             {csg3(CsgOp::kIntersection, {half_space({1, 1, 0}, 0, "g.a"),
                                                          sphere({0, 0, 0}, 1, "", "g.b")}),
                              half_space({0, 1, 1}, 0, "g.c")},
                             "g")),
            "g.c");
  EXPECT_EQ(error_field(half_space({0, 0, 1}, 0, "g")), "g");
  EXPECT_EQ(error_field(csg3(CsgOp::kIntersection,
                             {cuboid({0, 0, 0}, {1, 1, 1}), cuboid({2, 2, 2}, {3, 3, 3})}, "g")),
            "g");
  // program_bounds3 reports the same without throwing.
  EXPECT_FALSE(is_bounded(program_bounds3(compile_geometry3(half_space({0, 0, 1}, 0)))));
}

// Every point of the domain lies in its box, for shapes turned every way.
TEST(Bounds3, ContainsTheDomain) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const Similarity3 t{
        std::exp(u(rng)), {u(rng), u(rng), u(rng)}, 3 * u(rng), {u(rng), u(rng), u(rng)}};
    const Shape3 tree = transformed3(
        csg3(CsgOp::kUnion,
             {csg3(CsgOp::kDifference,
                   {cuboid({-1, -1, -1}, {1, 0.5, 0.2}), sphere({1, 1, 0}, 0.7)}),
              transformed3(cylinder({0, 0, 0}, 0.3, 2), t), frustum({0.5, 0, 0}, 0.5, 0.1, 1.5),
              csg3(CsgOp::kIntersection, {torus({0, 0, 1}, 1, 0.3), half_space({0, 1, 0}, 0.2)})}),
        t);
    const Program3 p = compile_geometry3(tree);
    const Box3 b = domain_bounds3(p);
    const double r = 2 * std::max({b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z});
    const Vec3 mid = 0.5 * (b.min + b.max);
    int inside = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 q = mid + r * Vec3{u(rng), u(rng), u(rng)};
      if (eval_sdf3(p.view(), q) > 0) continue;
      ++inside;
      EXPECT_TRUE(q.x >= b.min.x && q.x <= b.max.x && q.y >= b.min.y && q.y <= b.max.y &&
                  q.z >= b.min.z && q.z <= b.max.z);
    }
    EXPECT_GT(inside, 0);
  }
}

}  // namespace
}  // namespace meshd
