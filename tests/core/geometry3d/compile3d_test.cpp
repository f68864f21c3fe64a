// compile_geometry3 (postfix layout, folded frames, names, errors naming their fields) and the
// similarity algebra of shape3d.h.
#include "core/geometry3d/compile3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/common/error.h"
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

std::vector<double> params(const Program3& p, size_t i, size_t n) {
  return {p.params.begin() + p.code[i].operand, p.params.begin() + p.code[i].operand + n};
}

void expect_near(Vec3 a, Vec3 b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// ---- Similarities -------------------------------------------------------------------------

TEST(Similarity3, RotatesRightHandedAboutItsAxis) {
  const Similarity3 quarter{1, {0, 0, 5}, kPi / 2, {}};
  expect_near(apply(quarter, {1, 0, 0}), {0, 1, 0}, 1e-15);
  const Similarity3 t{2, {1, 0, 0}, kPi / 2, {1, 2, 3}};
  expect_near(apply(t, {0, 1, 0}), {1, 2, 5}, 1e-15);  // y turns into z, doubled, moved
  expect_near(rotate(t, {0, 0, 1}), {0, -1, 0}, 1e-15);
  expect_near(apply(Similarity3{}, {4, 5, 6}), {4, 5, 6}, 0);
}

TEST(Similarity3, ComposeAppliesTheInnerFirst) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 100; ++i) {
    const Similarity3 outer{
        std::exp(u(rng)), {u(rng), u(rng), u(rng)}, 2 * u(rng), {u(rng), u(rng), u(rng)}};
    const Similarity3 inner{
        std::exp(u(rng)), {u(rng), u(rng), u(rng)}, 2 * u(rng), {u(rng), u(rng), u(rng)}};
    const Vec3 p{u(rng), u(rng), u(rng)};
    expect_near(apply(compose(outer, inner), p), apply(outer, apply(inner, p)), 1e-12);
  }
  // Two half turns about the same axis are none.
  const Similarity3 half{1, {0, 1, 0}, kPi, {}};
  expect_near(apply(compose(half, half), {1, 2, 3}), {1, 2, 3}, 1e-15);
}

// ---- Layout -------------------------------------------------------------------------------

TEST(CompileGeometry3, PostfixLayoutAndFoldedFrames) {
  // (sphere u cuboid) \ (cylinder n half-space), then a torus and a cone in the union.
  const Shape3 tree = csg3(
      CsgOp::kUnion,
      {csg3(CsgOp::kDifference,
            {csg3(CsgOp::kUnion, {sphere({1, 2, 3}, 4), cuboid({0, 0, 0}, {2, 4, 6})}),
             csg3(CsgOp::kIntersection, {cylinder({1, 1, 1}, 0.5, 2), half_space({0, 0, 2}, 1)})}),
       torus({0, 0, 0}, 3, 1), frustum({0, 0, -1}, 2, 0, 3)});
  const Program3 p = compile_geometry3(tree);
  const std::vector<Op3> ops = {Op3::kSphere,    Op3::kCuboid, Op3::kMin,     Op3::kCylinder,
                                Op3::kHalfSpace, Op3::kMax,    Op3::kNegate,  Op3::kMax,
                                Op3::kTorus,     Op3::kMin,    Op3::kFrustum, Op3::kMin};
  ASSERT_EQ(p.code.size(), ops.size());
  for (size_t i = 0; i < ops.size(); ++i) EXPECT_EQ(p.code[i].op, ops[i]) << i;
  EXPECT_EQ(p.code[2].primitive, -1);
  EXPECT_EQ(p.code[10].primitive, 5);
  EXPECT_EQ(params(p, 0, 4), (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(params(p, 1, 15), (std::vector<double>{1, 2, 3, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 2, 3}));
  EXPECT_EQ(params(p, 3, 8), (std::vector<double>{1, 1, 2, 0, 0, 1, 0.5, 1}));  // centre of axis
  EXPECT_EQ(params(p, 4, 4), (std::vector<double>{0, 0, 1, 0.5}));              // unit normal
  EXPECT_EQ(params(p, 8, 8), (std::vector<double>{0, 0, 0, 0, 0, 1, 3, 1}));
  EXPECT_EQ(params(p, 10, 9), (std::vector<double>{0, 0, -1, 0, 0, 1, 2, 0, 3}));
  EXPECT_EQ(p.params.size(), 4u + 15u + 8u + 4u + 8u + 9u);
}

TEST(CompileGeometry3, TransformsFoldIntoTheFrame) {
  // Scale 2 about the origin, a quarter turn about x, then up by 10.
  const Program3 p = compile_geometry3(
      transformed3(csg3(CsgOp::kUnion, {cylinder({0, 0, 0}, 1, 4), half_space({0, 0, 3}, 3)}),
                   {2, {1, 0, 0}, kPi / 2, {0, 0, 10}}));
  const std::vector<double> c = params(p, 0, 8);
  expect_near({c[0], c[1], c[2]}, {0, -4, 10}, 1e-14);  // the axis's middle, (0, 0, 2) local
  expect_near({c[3], c[4], c[5]}, {0, -1, 0}, 1e-15);   // local z turns into -y
  EXPECT_DOUBLE_EQ(c[6], 2);
  EXPECT_DOUBLE_EQ(c[7], 4);
  // z <= 1 locally: -y <= 2 scaled, then the offset has no component along the normal.
  const std::vector<double> h = params(p, 1, 4);
  expect_near({h[0], h[1], h[2]}, {0, -1, 0}, 1e-15);
  EXPECT_NEAR(h[3], 2, 1e-14);
}

TEST(CompileGeometry3, NamesPrimitivesByKindWhenUnnamed) {
  const Program3 p =
      compile_geometry3(csg3(CsgOp::kUnion,
                             {sphere({0, 0, 0}, 1), cuboid({0, 0, 0}, {1, 1, 1}, "wall", "g.u[1]"),
                              sphere({2, 0, 0}, 1), half_space({1, 0, 0}, 0)},
                             "g"));
  ASSERT_EQ(p.primitives.size(), 4u);
  EXPECT_EQ(p.primitives[0].name, "sphere1");
  EXPECT_EQ(p.primitives[1].name, "wall");
  EXPECT_EQ(p.primitives[1].path, "g.u[1]");
  EXPECT_EQ(p.primitives[2].name, "sphere2");
  EXPECT_EQ(p.primitives[3].name, "half_space1");
  EXPECT_EQ(p.root_path, "g");
}

// ---- Errors -------------------------------------------------------------------------------

std::string error_field(const Shape3& shape) {
  try {
    compile_geometry3(shape);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return e.field();
  }
  return "(no error)";
}

TEST(CompileGeometry3, BadParametersNameTheirFields) {
  EXPECT_EQ(error_field(sphere({0, 0, 0}, 0, "", "g")), "g.sphere.radius");
  EXPECT_EQ(error_field(sphere({0, NAN, 0}, 1, "", "g")), "g.sphere.center");
  EXPECT_EQ(error_field(cuboid({0, 0, 0}, {1, 0, 1}, "", "g")), "g.cuboid.max");
  EXPECT_EQ(error_field(cylinder({0, 0, 0}, 1, -1, "g")), "g.cylinder.height");
  EXPECT_EQ(error_field(cylinder({0, 0, 0}, 0, 1, "g")), "g.cylinder.radius");
  EXPECT_EQ(error_field(frustum({0, 0, 0}, 0, 0, 1, "g")), "g.frustum.top_radius");
  EXPECT_EQ(error_field(frustum({0, 0, 0}, -1, 1, 1, "g")), "g.frustum.bottom_radius");
  EXPECT_EQ(error_field(frustum({0, 0, 0}, 1, 1, 0, "g")), "g.frustum.height");
  EXPECT_EQ(error_field(torus({0, 0, 0}, 1, 1, "g")), "g.torus.major_radius");
  EXPECT_EQ(error_field(torus({0, 0, 0}, 1, 0, "g")), "g.torus.minor_radius");
  EXPECT_EQ(error_field(half_space({0, 0, 0}, 1, "g")), "g.half_space.normal");
  EXPECT_EQ(error_field(csg3(CsgOp::kIntersection, {}, "g")), "g.intersection.shapes");
  EXPECT_EQ(error_field(transformed3(sphere({0, 0, 0}, 1), {1, {0, 0, 0}, 1, {}}, "g")),
            "g.transform.axis");
  EXPECT_EQ(error_field(transformed3(sphere({0, 0, 0}, 1), {0, {0, 0, 1}, 0, {}}, "g")),
            "g.transform.scale");
  // A zero axis is fine where there is no rotation.
  EXPECT_EQ(error_field(transformed3(sphere({0, 0, 0}, 1), {2, {0, 0, 0}, 0, {}}, "g")),
            "(no error)");
  // An error deep in the tree names the deep node.
  EXPECT_EQ(error_field(csg3(
                CsgOp::kUnion,
                {sphere({0, 0, 0}, 1, "", "g.u[0]"), sphere({0, 0, 0}, -2, "", "g.u[1]")}, "g")),
            "g.u[1].sphere.radius");
}

TEST(CompileGeometry3, TransformsThatOverflowNameTheShape) {
  const Shape3 huge = transformed3(
      transformed3(sphere({0, 0, 0}, 1, "", "g.s"), {1e100, {}, 0, {}}), {1e100, {}, 0, {}});
  EXPECT_EQ(error_field(huge), "g.s");
  const Shape3 tiny =
      transformed3(transformed3(cuboid({0, 0, 0}, {1, 1, 1}, "", "g.c"), {1e-200, {}, 0, {}}),
                   {1e-200, {}, 0, {}});
  EXPECT_EQ(error_field(tiny), "g.c");
}

TEST(CompileGeometry3, TooDeepATreeNamesTheNodeThatOverflows) {
  // union(s, union(s, ... union(s, s))): each level needs one more slot than the one inside.
  Shape3 tree = sphere({0, 0, 0}, 1);
  std::vector<std::string> paths;
  for (int level = 0; level < kMaxProgram3Stack; ++level) {
    paths.push_back("g" + std::to_string(level));
    tree = csg3(CsgOp::kUnion, {sphere({0, 0, 0}, 1), tree}, paths.back());
  }
  // The innermost union needs 2 slots, the k-th from inside k + 1: the last one needs 41.
  EXPECT_EQ(error_field(tree), paths.back());
  Shape3 shallower = std::get<Csg3>(tree.node).operands[1];
  EXPECT_EQ(error_field(shallower), "(no error)");
}

}  // namespace
}  // namespace meshd
