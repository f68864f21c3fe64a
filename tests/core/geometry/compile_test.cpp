// compile_geometry (postfix layout, names, the stack limit) and program_bounds.
#include "core/geometry/compile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/bounds.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::circle;
using testing::csg;
using testing::rectangle;
using testing::transformed;

std::vector<Op> ops(const Program& p) {
  std::vector<Op> out;
  for (const Instruction& i : p.code) out.push_back(i.op);
  return out;
}

// ---- Instruction layout ---------------------------------------------------------------------

TEST(CompileGeometry, PostfixLayoutOfASmallTree) {
  // (circle u rectangle) \ (ellipse n half-plane)
  const Shape tree =
      csg(CsgOp::kDifference, {csg(CsgOp::kUnion, {circle({1, 2}, 3), rectangle({-1, -2}, {3, 4})}),
                               csg(CsgOp::kIntersection, {Shape{Ellipse{{0.5, 0}, 2, 1}, "", ""},
                                                          Shape{HalfPlane{{0, 2}, 1}, "", ""}})});
  const Program p = compile_geometry(tree);
  EXPECT_EQ(ops(p), (std::vector<Op>{Op::kCircle, Op::kBox, Op::kMin, Op::kEllipse, Op::kHalfPlane,
                                     Op::kMax, Op::kNegate, Op::kMax}));
  // Primitives are numbered in tree order; operations carry -1.
  const std::vector<int32_t> prim = {0, 1, -1, 2, 3, -1, -1, -1};
  for (size_t i = 0; i < p.code.size(); ++i) EXPECT_EQ(p.code[i].primitive, prim[i]) << i;
  ASSERT_EQ(p.primitives.size(), 4u);

  // Parameters at each primitive's operand, in the layout program.h documents.
  auto params = [&](size_t i, size_t n) {
    return std::vector<double>(p.params.begin() + p.code[i].operand,
                               p.params.begin() + p.code[i].operand + n);
  };
  EXPECT_EQ(params(0, 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(params(1, 6),
            (std::vector<double>{1, 1, 2, 3, 1, 0}));  // centre, half extents, cos sin
  EXPECT_EQ(params(3, 6), (std::vector<double>{0.5, 0, 2, 1, 1, 0}));
  EXPECT_EQ(params(4, 3), (std::vector<double>{0, 1, 0.5}));  // unit normal, offset / |n|
  EXPECT_EQ(p.params.size(), 3u + 6u + 6u + 3u);
  // Every primitive's parameters are its own: offsets increase and do not overlap.
  EXPECT_EQ(p.code[0].operand, 0u);
  EXPECT_EQ(p.code[1].operand, 3u);
  EXPECT_EQ(p.code[3].operand, 9u);
  EXPECT_EQ(p.code[4].operand, 15u);
}

// Islands with lakes: a union of ten squares, each minus nine disks, indexes the union and each
// island's lakes, one inside the other; the squares alone, or one island, index one level.
TEST(CompileGeometry, IslandsWithLakesNestIndexedUnions) {
  auto island = [](double x) {
    std::vector<Shape> ops{rectangle({x, 0}, {x + 0.9, 0.9})};
    for (int k = 0; k < 9; ++k) ops.push_back(circle({x + 0.1 + 0.08 * k, 0.45}, 0.03));
    return csg(CsgOp::kDifference, ops);
  };
  std::vector<Shape> islands, squares;
  for (int i = 0; i < 10; ++i) {
    islands.push_back(island(i));
    squares.push_back(rectangle({1.0 * i, 0}, {i + 0.9, 0.9}));
  }
  EXPECT_TRUE(nests_indexed_unions(compile_geometry(csg(CsgOp::kUnion, islands))));
  EXPECT_FALSE(nests_indexed_unions(compile_geometry(csg(CsgOp::kUnion, squares))));
  EXPECT_FALSE(nests_indexed_unions(compile_geometry(island(0))));
}

TEST(CompileGeometry, PolygonParameters) {
  const std::vector<Vec2> v = {{0, 0}, {2, 0}, {1, 1.5}};
  const Program p = compile_geometry(Shape{Polygon{v}, "", ""});
  ASSERT_EQ(p.code.size(), 1u);
  EXPECT_EQ(p.code[0].op, Op::kPolygon);
  EXPECT_EQ(p.params, (std::vector<double>{3, 0, 0, 2, 0, 1, 1.5, 1}));  // counter-clockwise
  EXPECT_EQ(p.primitives[0].corners, (std::vector<double>{0, 0, 2, 0, 1, 1.5}));
  const Program cw = compile_geometry(Shape{Polygon{{v[2], v[1], v[0]}}, "", ""});
  EXPECT_EQ(cw.params.back(), -1);
}

TEST(CompileGeometry, NaryOperationsFoldLeftInTwoStackSlots) {
  std::vector<Shape> five;
  for (int i = 0; i < 5; ++i) five.push_back(circle({2.0 * i, 0}, 0.5 + 0.1 * i));
  for (CsgOp op : {CsgOp::kUnion, CsgOp::kIntersection, CsgOp::kDifference}) {
    const Program p = compile_geometry(csg(op, five));
    std::vector<Op> want = {Op::kCircle};
    for (int i = 1; i < 5; ++i) {
      want.push_back(Op::kCircle);
      if (op == CsgOp::kDifference) want.push_back(Op::kNegate);
      want.push_back(op == CsgOp::kUnion ? Op::kMin : Op::kMax);
    }
    EXPECT_EQ(ops(p), want);
    // The value agrees with folding the operands' distances.
    for (Vec2 q : {Vec2{0, 0}, Vec2{3.9, 0.2}, Vec2{8, 0}, Vec2{-1, 1}}) {
      double want_d = std::hypot(q.x, q.y) - 0.5;
      for (int i = 1; i < 5; ++i) {
        const double d = std::hypot(q.x - 2.0 * i, q.y) - (0.5 + 0.1 * i);
        want_d = op == CsgOp::kUnion          ? std::min(want_d, d)
                 : op == CsgOp::kIntersection ? std::max(want_d, d)
                                              : std::max(want_d, -d);
      }
      EXPECT_NEAR(eval_sdf(p.view(), q), want_d, 1e-15);
    }
  }
  // A thousand operands still need two slots: no stack error.
  std::vector<Shape> many(1000, circle({0, 0}, 1));
  EXPECT_NO_THROW(compile_geometry(csg(CsgOp::kUnion, many)));
}

// ---- Names --------------------------------------------------------------------------------------

TEST(CompileGeometry, DefaultNamesCountPerKind) {
  const Shape tree =
      csg(CsgOp::kUnion,
          {circle({0, 0}, 1), rectangle({0, 0}, {1, 1}), circle({3, 0}, 1),
           Shape{Polygon{{{0, 0}, {1, 0}, {0, 1}}}, "", ""}, Shape{Ellipse{{0, 0}, 2, 1}, "", ""},
           rectangle({2, 2}, {3, 3}), Shape{HalfPlane{{1, 0}, 5}, "", ""}, circle({6, 0}, 1)});
  const Program p = compile_geometry(tree);
  std::vector<std::string> names;
  for (const auto& prim : p.primitives) names.push_back(prim.name);
  EXPECT_EQ(names, (std::vector<std::string>{"circle1", "rectangle1", "circle2", "polygon1",
                                             "ellipse1", "rectangle2", "half_plane1", "circle3"}));
}

TEST(CompileGeometry, GivenNamesAndPathsAreKept) {
  Shape outer = rectangle({-1, -1}, {1, 1}, "outer");
  outer.path = "geometry.difference.shapes[0]";
  Shape hole = circle({0, 0}, 0.5, "hole");
  hole.path = "geometry.difference.shapes[1]";
  Shape other = circle({5, 5}, 0.5);
  other.path = "geometry.difference.shapes[2]";
  // A name under a transform is kept too.
  const Program p =
      compile_geometry(csg(CsgOp::kDifference, {outer, transformed(hole, 1, 0, {0.1, 0}), other}));
  ASSERT_EQ(p.primitives.size(), 3u);
  EXPECT_EQ(p.primitives[0].name, "outer");
  EXPECT_EQ(p.primitives[0].path, "geometry.difference.shapes[0]");
  EXPECT_EQ(p.primitives[1].name, "hole");
  EXPECT_EQ(p.primitives[1].path, "geometry.difference.shapes[1]");
  EXPECT_EQ(p.primitives[2].name.rfind("circle", 0), 0u) << p.primitives[2].name;
  EXPECT_EQ(p.primitives[2].path, "geometry.difference.shapes[2]");
  // Names of a tree with the same name twice are kept as given (one boundary group).
  const Program twice =
      compile_geometry(csg(CsgOp::kUnion, {circle({0, 0}, 1, "wall"), circle({3, 0}, 1, "wall")}));
  EXPECT_EQ(twice.primitives[0].name, "wall");
  EXPECT_EQ(twice.primitives[1].name, "wall");
}

// ---- Stack depth --------------------------------------------------------------------------------

// u(c, u(c, u(c, ... u(c, c)))) nested `levels` deep, right-heavy: each level keeps one value
// on the stack while its right operand is evaluated, so the tree needs levels + 1 slots. Paths
// name each node as a request would.
Shape right_deep(int levels, std::vector<std::string>* paths) {
  std::string path = "geometry";
  std::vector<std::string> node_paths;
  for (int i = 0; i < levels; ++i) {
    node_paths.push_back(path);
    path += ".union.shapes[1]";
  }
  Shape s = circle({0, 0}, 1.0 + levels);
  s.path = path;
  for (int i = levels - 1; i >= 0; --i) {
    Shape left = circle({0, 0}, 1.0 + i);
    left.path = node_paths[i] + ".union.shapes[0]";
    s = csg(CsgOp::kUnion, {left, s}, node_paths[i]);
  }
  if (paths != nullptr) *paths = node_paths;
  return s;
}

TEST(CompileGeometry, DeepestTreeThatFitsEvaluatesCorrectly) {
  // kMaxProgramStack - 1 levels need exactly kMaxProgramStack slots.
  const Program p = compile_geometry(right_deep(kMaxProgramStack - 1, nullptr));
  EXPECT_EQ(p.primitives.size(), static_cast<size_t>(kMaxProgramStack));
  // The union of concentric circles of radii 1..40 is the largest one.
  EXPECT_DOUBLE_EQ(eval_sdf(p.view(), {0, 0}), -double(kMaxProgramStack));
  EXPECT_DOUBLE_EQ(eval_sdf(p.view(), {50, 0}), 50.0 - kMaxProgramStack);
}

TEST(CompileGeometry, TooDeepTreeNamesTheNodeThatOverflows) {
  std::vector<std::string> paths;
  const Shape tree = right_deep(kMaxProgramStack + 5, &paths);
  try {
    compile_geometry(tree);
    FAIL() << "no error for a tree needing " << kMaxProgramStack + 6 << " slots";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    // The node needing kMaxProgramStack + 1 slots is the one kMaxProgramStack levels above the
    // innermost union: with 45 levels, paths[5].
    EXPECT_EQ(e.field(), paths[5]);
    EXPECT_NE(std::string(e.what()).find(paths[5]), std::string::npos) << e.what();
    EXPECT_NE(e.detail().find(std::to_string(kMaxProgramStack)), std::string::npos) << e.detail();
  }
  // A left-heavy tree of the same depth needs only two slots.
  Shape left = circle({0, 0}, 1);
  for (int i = 0; i < 200; ++i) left = csg(CsgOp::kUnion, {left, circle({0, 0}, 1)});
  EXPECT_NO_THROW(compile_geometry(left));
  // The size field's shapes are checked the same way.
  SizeFieldSpec spec;
  DistanceSize d;
  d.shape = right_deep(kMaxProgramStack + 1, nullptr);
  spec.terms.push_back(d);
  EXPECT_THROW(compile_size_field(spec), Error);
}

// ---- Bounds -------------------------------------------------------------------------------------

void expect_box(const Box& b, Box want, double tol = 1e-14) {
  EXPECT_NEAR(b.min.x, want.min.x, tol);
  EXPECT_NEAR(b.min.y, want.min.y, tol);
  EXPECT_NEAR(b.max.x, want.max.x, tol);
  EXPECT_NEAR(b.max.y, want.max.y, tol);
}

TEST(ProgramBounds, UnionIntersectionDifference) {
  const Shape a = circle({0, 0}, 1), b = rectangle({0.5, -3}, {4, 0.25});
  expect_box(program_bounds(compile_geometry(a)), {{-1, -1}, {1, 1}});
  expect_box(program_bounds(compile_geometry(csg(CsgOp::kUnion, {a, b}))), {{-1, -3}, {4, 1}});
  expect_box(program_bounds(compile_geometry(csg(CsgOp::kIntersection, {a, b}))),
             {{0.5, -1}, {1, 0.25}});
  // A difference keeps its base's box, whatever it removes.
  expect_box(program_bounds(compile_geometry(csg(CsgOp::kDifference, {a, b}))), {{-1, -1}, {1, 1}});
  expect_box(program_bounds(compile_geometry(csg(CsgOp::kDifference, {b, a}))),
             {{0.5, -3}, {4, 0.25}});
  // Disjoint intersection: empty.
  const Box empty =
      program_bounds(compile_geometry(csg(CsgOp::kIntersection, {a, circle({5, 0}, 1)})));
  EXPECT_TRUE(is_empty(empty));
  // Polygon: its vertices' box.
  expect_box(program_bounds(compile_geometry(Shape{Polygon{{{0, 0}, {2, -1}, {1, 3}}}, "", ""})),
             {{0, -1}, {2, 3}});
}

TEST(ProgramBounds, HalfPlanes) {
  const Shape h{HalfPlane{{0, 1}, 0.5}, "", ""};  // y <= 0.5
  const Box alone = program_bounds(compile_geometry(h));
  EXPECT_FALSE(is_bounded(alone));
  EXPECT_FALSE(is_empty(alone));
  // Cut off by a bounded operand: that operand's box (a box bound, not the exact cut).
  const Box cut =
      program_bounds(compile_geometry(csg(CsgOp::kIntersection, {h, circle({0, 0}, 1)})));
  EXPECT_TRUE(is_bounded(cut));
  expect_box(cut, {{-1, -1}, {1, 1}});
  // Union with a half-plane and a half-plane minus a disk stay unbounded.
  EXPECT_FALSE(
      is_bounded(program_bounds(compile_geometry(csg(CsgOp::kUnion, {h, circle({0, 0}, 1)})))));
  EXPECT_FALSE(is_bounded(
      program_bounds(compile_geometry(csg(CsgOp::kDifference, {h, circle({0, 0}, 1)})))));
  // A disk minus a half-plane keeps the disk's box.
  expect_box(program_bounds(compile_geometry(csg(CsgOp::kDifference, {circle({0, 0}, 1), h}))),
             {{-1, -1}, {1, 1}});
}

TEST(ProgramBounds, RotatedShapes) {
  // [-1,1] x [-0.5,0.5] rotated by 30 degrees: extents |c| hx + |s| hy and |s| hx + |c| hy.
  const double a = kPi / 6, c = std::cos(a), s = std::sin(a);
  const Box rect =
      program_bounds(compile_geometry(transformed(rectangle({-1, -0.5}, {1, 0.5}), 2, a, {3, -1})));
  const double ex = 2 * (c * 1 + s * 0.5), ey = 2 * (s * 1 + c * 0.5);
  expect_box(rect, {{3 - ex, -1 - ey}, {3 + ex, -1 + ey}});
  // Exactly the box of the rotated corners.
  const Program rp = compile_geometry(transformed(rectangle({-1, -0.5}, {1, 0.5}), 2, a, {3, -1}));
  const auto& corners = rp.primitives[0].corners;
  ASSERT_EQ(corners.size(), 8u);
  double minx = INFINITY, maxx = -INFINITY;
  for (size_t i = 0; i < 8; i += 2)
    minx = std::min(minx, corners[i]), maxx = std::max(maxx, corners[i]);
  EXPECT_NEAR(rect.min.x, minx, 1e-14);
  EXPECT_NEAR(rect.max.x, maxx, 1e-14);

  // Ellipse with semi axes 2, 1 rotated by 30 degrees: sqrt((a c)^2 + (b s)^2), exact (tight).
  const Box ell = program_bounds(
      compile_geometry(transformed(Shape{Ellipse{{0, 0}, 2, 1}, "", ""}, 1, a, {0, 0})));
  const double exe = std::hypot(2 * c, 1 * s), eye = std::hypot(2 * s, 1 * c);
  expect_box(ell, {{-exe, -eye}, {exe, eye}});
  // Tight: the rotated ellipse reaches its box's right side.
  double best = INFINITY;
  for (int k = 0; k < 20000; ++k) {
    const double t = 2 * kPi * k / 20000;
    const Vec2 q{2 * std::cos(t) * c - std::sin(t) * s, 2 * std::cos(t) * s + std::sin(t) * c};
    best = std::min(best, exe - q.x);
  }
  EXPECT_NEAR(best, 0.0, 1e-6);
  // A rotated half-plane is still unbounded; a rotated polygon has its rotated vertices' box.
  EXPECT_FALSE(is_bounded(program_bounds(
      compile_geometry(transformed(Shape{HalfPlane{{1, 0}, 0}, "", ""}, 1, a, {0, 0})))));
  const Box tri = program_bounds(compile_geometry(
      transformed(Shape{Polygon{{{0, 0}, {1, 0}, {0, 1}}}, "", ""}, 1, kPi / 2, {0, 0})));
  expect_box(tri, {{-1, 0}, {0, 1}});
}

}  // namespace
}  // namespace meshd
