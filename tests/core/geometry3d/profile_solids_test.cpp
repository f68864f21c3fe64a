// Extrusions and revolutions of plane profiles: their distances equal those of the primitives
// they reproduce (a box, a capped cylinder, a torus, a cone) everywhere, under similarities too;
// their boxes; their sharp features (rims, vertical edges, a cone's apex, no false apex at a
// flat end); the compiler's errors name the profile's fields.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/common/error.h"
#include "core/geometry3d/bounds3.h"
#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/sharp_features3.h"
#include "tests/core/geometry/shape_builders.h"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

Shape3 extrusion(Shape profile, double height, std::string path = "geometry") {
  return Shape3{Extrusion{std::move(profile), height}, "", std::move(path)};
}

Shape3 revolution(Shape profile, std::string path = "geometry") {
  return Shape3{Revolution{std::move(profile)}, "", std::move(path)};
}

Similarity3 tilt() {
  Similarity3 t;
  t.scale = 1.7;
  t.axis = {1, 2, -0.5};
  t.angle = 0.8;
  t.offset = {0.3, -1.1, 2};
  return t;
}

// The two shapes' distances agree at random points in and around them.
void expect_same_distance(const Shape3& a, const Shape3& b, double extent, double tol) {
  const Program3 pa = compile_geometry3(a), pb = compile_geometry3(b);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-extent, extent);
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    ASSERT_NEAR(eval_sdf3(pa.view(), p), eval_sdf3(pb.view(), p), tol)
        << p.x << " " << p.y << " " << p.z;
  }
}

TEST(ProfileSolids, AnExtrudedRectangleIsABox) {
  const Shape profile = testing::rectangle({-1, -0.5}, {1, 0.5});
  const Shape3 box = testing::cuboid({-1, -0.5, 0}, {1, 0.5, 2});
  expect_same_distance(extrusion(profile, 2), box, 3, 1e-12);
  expect_same_distance(testing::transformed3(extrusion(profile, 2), tilt()),
                       testing::transformed3(box, tilt()), 6, 1e-11);
  const Box3 b =
      program_bounds3(compile_geometry3(testing::transformed3(extrusion(profile, 2), tilt())));
  const Box3 c = program_bounds3(compile_geometry3(testing::transformed3(box, tilt())));
  EXPECT_NEAR(b.min.x, c.min.x, 1e-12);
  EXPECT_NEAR(b.max.z, c.max.z, 1e-12);
}

TEST(ProfileSolids, RevolvedRectangleAndCircleAreACylinderAndATorus) {
  // A solid on its axis: the profile symmetric about it.
  expect_same_distance(revolution(testing::rectangle({-1, 0}, {1, 2})),
                       testing::cylinder({0, 0, 0}, 1, 2), 3, 1e-12);
  expect_same_distance(
      revolution(Shape{Polygon{{{-1, 0}, {1, 0}, {0, 1}}}, "", "geometry.revolution.profile"}),
      testing::frustum({0, 0, 0}, 1, 0, 1), 3, 1e-12);
  expect_same_distance(testing::transformed3(revolution(testing::circle({2, 0}, 0.5)), tilt()),
                       testing::transformed3(testing::torus({0, 0, 0}, 2, 0.5), tilt()), 6, 1e-11);
}

TEST(ProfileSolids, SharpFeaturesPinRimsVerticalEdgesAndApexesOnly) {
  const double spacing = 0.125;
  // The extruded square: its 8 corners, samples on its 4 vertical edges and along both rims.
  const Program3 box = compile_geometry3(extrusion(testing::rectangle({-1, -1}, {1, 1}), 2));
  const std::vector<Vec3> f = sharp_features3(box, spacing);
  int corners = 0, vertical = 0, rims = 0;
  for (Vec3 p : f) {
    EXPECT_NEAR(eval_sdf3(box.view(), p), 0.0, 1e-9);
    const bool on_side_edge =
        std::fabs(std::fabs(p.x) - 1) < 1e-9 && std::fabs(std::fabs(p.y) - 1) < 1e-9;
    const bool on_end = std::fabs(p.z) < 1e-9 || std::fabs(p.z - 2) < 1e-9;
    corners += on_side_edge && on_end;
    vertical += on_side_edge && !on_end;
    rims += on_end && !on_side_edge;
    EXPECT_TRUE(on_side_edge || on_end) << p.x << " " << p.y << " " << p.z;
  }
  EXPECT_EQ(corners, 8);
  EXPECT_EQ(vertical, 4 * 15);  // 2 / 0.125 segments per edge
  // Each rim is 8 long, sampled 0.75 to 1.5 spacings apart.
  EXPECT_GE(rims, 2 * 8 / (1.5 * spacing) - 8);
  EXPECT_LE(rims, 2 * 8 / (0.75 * spacing));

  // A revolved triangle is a cone: its base rim and its apex, not the base's centre.
  const Program3 cone = compile_geometry3(
      revolution(Shape{Polygon{{{-1, 0}, {1, 0}, {0, 1}}}, "", "geometry.revolution.profile"}));
  int apex = 0, centre = 0, rim = 0;
  for (Vec3 p : sharp_features3(cone, spacing)) {
    apex += norm(p - Vec3{0, 0, 1}) < 1e-9;
    centre += norm(p) < 1e-9;
    rim += std::fabs(std::hypot(p.x, p.y) - 1) < 1e-9 && std::fabs(p.z) < 1e-9;
  }
  EXPECT_EQ(apex, 1);
  EXPECT_EQ(centre, 0);
  EXPECT_EQ(rim, static_cast<int>(std::ceil(2 * std::numbers::pi / spacing)));
}

TEST(ProfileSolids, ErrorsNameTheProfilesFields) {
  try {
    compile_geometry3(extrusion(testing::rectangle({0, 0}, {1, 1}), -1, "volume.geometry"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "volume.geometry.extrusion.height");
  }
  try {
    compile_geometry3(extrusion(testing::half_plane({0, 1}, 0), 1, "volume.geometry"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "volume.geometry.extrusion.profile");
    EXPECT_NE(e.detail().find("bounded"), std::string::npos) << e.detail();
  }
  for (const Shape& profile : {testing::rectangle({-2, 0}, {-1, 1}),   // all at x < 0
                               testing::rectangle({0, 0}, {1, 1})}) {  // touching the axis
    try {
      compile_geometry3(revolution(profile, "volume.geometry"));
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.field(), "volume.geometry.revolution.profile");
    }
  }
}

}  // namespace
}  // namespace meshd
