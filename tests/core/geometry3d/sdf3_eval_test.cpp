// The 3D signed-distance evaluator (sdf3_eval.cuh) through compile_geometry3: each primitive at
// points whose distance is known by hand (inside, outside, near edges and corners, on the axis,
// at a cone's apex), transforms folded into the primitives, CSG, and the owner output.
#include "core/geometry3d/sdf3_eval.cuh"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/geometry3d/compile3d.h"
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
constexpr double kTol = 1e-13;

double sdf(const Shape3& shape, Vec3 p) { return eval_sdf3(compile_geometry3(shape).view(), p); }

TEST(Sdf3, Sphere) {
  const Shape3 s = sphere({1, 2, 3}, 2);
  EXPECT_NEAR(sdf(s, {1, 2, 3}), -2, kTol);
  EXPECT_NEAR(sdf(s, {1, 2, 6}), 1, kTol);
  EXPECT_NEAR(sdf(s, {1, 2, 4}), -1, kTol);
  EXPECT_NEAR(sdf(s, {3, 2, 3}), 0, kTol);
}

TEST(Sdf3, CuboidFacesEdgesAndCorners) {
  const Shape3 b = cuboid({0, 0, 0}, {2, 1, 4});
  EXPECT_NEAR(sdf(b, {1, 0.5, 2}), -0.5, kTol);          // centre: the nearest face
  EXPECT_NEAR(sdf(b, {1, 0.2, 2}), -0.2, kTol);          // inside, near a face
  EXPECT_NEAR(sdf(b, {1, 0.5, 5}), 1, kTol);             // outside a face
  EXPECT_NEAR(sdf(b, {3, 2, 2}), std::sqrt(2.0), kTol);  // outside an edge: rounded
  EXPECT_NEAR(sdf(b, {3, 2, 5}), std::sqrt(3.0), kTol);  // outside a corner: rounded
  EXPECT_NEAR(sdf(b, {2, 1, 4}), 0, kTol);               // at a corner
  EXPECT_NEAR(sdf(b, {1.9, 0.95, 3.99}), -0.01, kTol);   // inside a corner
}

TEST(Sdf3, CylinderOnTheAxisAtTheRimsAndCaps) {
  const Shape3 c = cylinder({0, 0, 0}, 1, 2);
  EXPECT_NEAR(sdf(c, {0, 0, 1}), -1, kTol);      // on the axis, at the middle
  EXPECT_NEAR(sdf(c, {0, 0, 0.5}), -0.5, kTol);  // on the axis, near the bottom cap
  EXPECT_NEAR(sdf(c, {0, 0, -1}), 1, kTol);      // on the axis, below
  EXPECT_NEAR(sdf(c, {0, 0, 3}), 1, kTol);       // on the axis, above
  EXPECT_NEAR(sdf(c, {2, 0, 1}), 1, kTol);       // beside the side
  EXPECT_NEAR(sdf(c, {0, -3, 1}), 2, kTol);
  EXPECT_NEAR(sdf(c, {2, 0, 3}), std::sqrt(2.0), kTol);  // outside the top rim: rounded
  EXPECT_NEAR(sdf(c, {0.6, 0.8, -1}), 1, kTol);          // below the bottom cap, inside its disk
  EXPECT_NEAR(sdf(c, {0.5, 0, 1.9}), -0.1, kTol);        // nearest the top cap
  EXPECT_NEAR(sdf(c, {0, 0.9, 1.95}), -0.05, kTol);      // inside near the rim: the cap wins
  EXPECT_NEAR(sdf(c, {0, 0.97, 1.9}), -0.03, kTol);      // ... the side wins
  EXPECT_NEAR(sdf(c, {1, 0, 2}), 0, kTol);               // on the rim
}

TEST(Sdf3, ConeAtTheApexAndOnTheAxis) {
  // Apex at (0, 0, 1); the side is the line r + z = 1 in the (r, z) half-plane.
  const Shape3 c = frustum({0, 0, 0}, 1, 0, 1);
  const double s2 = std::sqrt(2.0);
  EXPECT_NEAR(sdf(c, {0, 0, 1}), 0, kTol);            // the apex
  EXPECT_NEAR(sdf(c, {0, 0, 2}), 1, kTol);            // above the apex on the axis
  EXPECT_NEAR(sdf(c, {0, 0, 0.5}), -0.5 / s2, kTol);  // inside on the axis: the side is nearer
  EXPECT_NEAR(sdf(c, {0, 0, 0.2}), -0.2, kTol);       // ... the base is nearer
  EXPECT_NEAR(sdf(c, {0, 0, -1}), 1, kTol);           // below the base on the axis
  EXPECT_NEAR(sdf(c, {0.1, 0, 1}), 0.1 / s2, kTol);   // beside the apex: the side's foot
  EXPECT_NEAR(sdf(c, {0, -0.1, 1}), 0.1 / s2, kTol);  // the same, another half-plane
  EXPECT_NEAR(sdf(c, {0.5, 0, 1.5}), std::sqrt(0.5), kTol);  // beyond the apex: the apex itself
  EXPECT_NEAR(sdf(c, {2, 0, 0}), 1, kTol);                   // beside the base rim
  EXPECT_NEAR(sdf(c, {1, 0, 1}), 1 / s2, kTol);              // outside the side
  EXPECT_NEAR(sdf(c, {0, 0, 1 - 1e-9}), -1e-9 / s2, 1e-15);  // just below the apex
}

TEST(Sdf3, FrustumSideRimsAndCaps) {
  // rb = 2, rt = 1, h = 1: the side runs from (2, 0) to (1, 1) in the (r, z) half-plane.
  const Shape3 f = frustum({0, 0, 0}, 2, 1, 1);
  EXPECT_NEAR(sdf(f, {0, 0, 2}), 1, kTol);                   // above the top cap
  EXPECT_NEAR(sdf(f, {0.5, 0, 1.5}), 0.5, kTol);             // above the top cap, off the axis
  EXPECT_NEAR(sdf(f, {0, 0, 0.5}), -0.5, kTol);              // inside on the axis
  EXPECT_NEAR(sdf(f, {3, 0, 0.5}), std::sqrt(1.25), kTol);   // beyond the bottom rim
  EXPECT_NEAR(sdf(f, {1.5, 0, 1.5}), std::sqrt(0.5), kTol);  // beyond the top rim
  EXPECT_NEAR(sdf(f, {2, 0, 1}), 1 / std::sqrt(2.0), kTol);  // outside the side's middle
  EXPECT_NEAR(sdf(f, {0, 1.5, 0.5}), 0, kTol);               // on the side
  // An inverted cone: apex at the base, radius 1 at the top.
  const Shape3 v = frustum({0, 0, 0}, 0, 1, 1);
  EXPECT_NEAR(sdf(v, {0, 0, 0}), 0, kTol);
  EXPECT_NEAR(sdf(v, {0, 0, -1}), 1, kTol);
  EXPECT_NEAR(sdf(v, {0, 0, 0.5}), -0.5 / std::sqrt(2.0), kTol);
}

TEST(Sdf3, Torus) {
  const Shape3 t = torus({0, 0, 0}, 2, 0.5);
  EXPECT_NEAR(sdf(t, {2, 0, 0}), -0.5, kTol);                  // on the tube's centre line
  EXPECT_NEAR(sdf(t, {0, 0, 0}), 1.5, kTol);                   // the centre of the hole
  EXPECT_NEAR(sdf(t, {0, 0, 1}), std::sqrt(5.0) - 0.5, kTol);  // on the axis
  EXPECT_NEAR(sdf(t, {3, 0, 0}), 0.5, kTol);
  EXPECT_NEAR(sdf(t, {0, 2.5, 0}), 0, kTol);
  EXPECT_NEAR(sdf(t, {0, -2, 1}), 0.5, kTol);
}

TEST(Sdf3, HalfSpace) {
  const Shape3 h = half_space({0, 0, 2}, 2);  // z <= 1
  EXPECT_NEAR(sdf(h, {5, 5, 3}), 2, kTol);
  EXPECT_NEAR(sdf(h, {-5, 5, 0}), -1, kTol);
}

// A cuboid rotated, scaled and translated equals the axis-aligned cuboid computed by hand.
TEST(Sdf3, TransformedCuboidEqualsTheHandComputedOne) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-6, 14);
  // About z by 90 degrees, scale 2, then (10, 0, 0): local x turns into world y.
  const Shape3 a =
      transformed3(cuboid({-1, -0.5, -2}, {1, 0.5, 2}), {2, {0, 0, 1}, kPi / 2, {10, 0, 0}});
  const Shape3 a_ref = cuboid({9, -2, -4}, {11, 2, 4});
  // About (1, 1, 1) by 120 degrees: (x, y, z) -> (z, x, y); then scaled by 0.5 about the origin
  // and moved by (1, 2, 3), nested as two transforms.
  const Shape3 b =
      transformed3(transformed3(cuboid({0, 0, 0}, {1, 2, 3}), {1, {1, 1, 1}, 2 * kPi / 3, {}}),
                   {0.5, {0, 0, 1}, 0, {1, 2, 3}});
  const Shape3 b_ref = cuboid({1, 2, 3}, {2.5, 2.5, 4});
  const Program3 pa = compile_geometry3(a), pa_ref = compile_geometry3(a_ref);
  const Program3 pb = compile_geometry3(b), pb_ref = compile_geometry3(b_ref);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng) - 4, u(rng) - 4};
    EXPECT_NEAR(eval_sdf3(pa.view(), p), eval_sdf3(pa_ref.view(), p), 1e-12);
    const Vec3 q = 0.25 * p;
    EXPECT_NEAR(eval_sdf3(pb.view(), q), eval_sdf3(pb_ref.view(), q), 1e-12);
  }
}

// A cylinder lying along x (rotated about y) and scaled: distances scale with it.
TEST(Sdf3, TransformedCylinderAndTorus) {
  const Shape3 c = transformed3(cylinder({0, 0, 0}, 1, 2), {3, {0, 1, 0}, kPi / 2, {0, 0, 0}});
  EXPECT_NEAR(sdf(c, {3, 0, 0}), -3, 1e-12);  // the middle of the axis, now along +x
  EXPECT_NEAR(sdf(c, {3, 5, 0}), 2, 1e-12);
  EXPECT_NEAR(sdf(c, {-1, 0, 0}), 1, 1e-12);
  EXPECT_NEAR(sdf(c, {7, 0, 0}), 1, 1e-12);
  const Shape3 t = transformed3(torus({0, 0, 0}, 2, 0.5), {2, {1, 0, 0}, kPi / 2, {0, 0, 1}});
  EXPECT_NEAR(sdf(t, {0, 0, 5}), -1, 1e-12);  // the tube's centre line lies in the y = 0 plane
  EXPECT_NEAR(sdf(t, {0, 0, 1}), 3, 1e-12);   // the centre of the hole
}

TEST(Sdf3, CsgOperations) {
  const Shape3 a = sphere({0, 0, 0}, 1), b = sphere({1.5, 0, 0}, 1);
  const Vec3 p{0.75, 0, 0};
  const double da = sdf(a, p), db = sdf(b, p);
  EXPECT_DOUBLE_EQ(sdf(csg3(CsgOp::kUnion, {a, b}), p), std::min(da, db));
  EXPECT_DOUBLE_EQ(sdf(csg3(CsgOp::kIntersection, {a, b}), p), std::max(da, db));
  EXPECT_DOUBLE_EQ(sdf(csg3(CsgOp::kDifference, {a, b}), p), std::max(da, -db));
  // A box with a spherical bite out of one corner: the corner is gone, the far one stays.
  const Shape3 bitten =
      csg3(CsgOp::kDifference, {cuboid({0, 0, 0}, {1, 1, 1}), sphere({1, 1, 1}, 0.5)});
  EXPECT_NEAR(sdf(bitten, {1, 1, 1}), 0.5, kTol);
  EXPECT_NEAR(sdf(bitten, {0, 0, 0}), 0, kTol);
  EXPECT_NEAR(sdf(bitten, {0.5, 0.5, 0.5}), -0.5 * std::sqrt(3.0) + 0.5, kTol);
}

TEST(Sdf3, OwnerIsTheNearestPrimitive) {
  const Program3 p = compile_geometry3(csg3(
      CsgOp::kDifference, {cuboid({0, 0, 0}, {4, 4, 4}, "box"), sphere({4, 4, 4}, 1, "bite")}));
  int owner = -1;
  eval_sdf3(p.view(), {2, 2, 0.1}, &owner);
  EXPECT_EQ(p.primitives[owner].name, "box");
  eval_sdf3(p.view(), {3.4, 3.4, 3.4}, &owner);
  EXPECT_EQ(p.primitives[owner].name, "bite");
}

}  // namespace
}  // namespace meshd
