// compile_problem: the errors that name a request field, the box, and the fixed points (given
// ones first, duplicates dropped, corners detected).
#include "core/distmesh/compiled_problem.h"

#include <gtest/gtest.h>

#include <string>

#include "core/common/error.h"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

Shape csg(CsgOp op, std::vector<Shape> operands) {
  return Shape{Csg{op, std::move(operands)}, "", ""};
}

// The field of the Error(kInvalidArgument) that compiling `p` throws; "" when none.
std::string error_field(const Problem& p) {
  try {
    compile_problem(p);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
    return e.field();
  }
  return "";
}

TEST(CompileProblem, UnboundedHalfPlaneNeedsABox) {
  Problem p;
  p.h0 = 0.1;
  p.geometry = Shape{HalfPlane{{0, 1}, 0}, "", ""};
  EXPECT_EQ(error_field(p), "bbox");
  // With a box it compiles, and the box is the given one.
  p.bbox = Box{{-1, -2}, {3, 0.5}};
  const CompiledProblem c = compile_problem(p);
  EXPECT_EQ(c.bbox.min.x, -1.0);
  EXPECT_EQ(c.bbox.min.y, -2.0);
  EXPECT_EQ(c.bbox.max.x, 3.0);
  EXPECT_EQ(c.bbox.max.y, 0.5);
  // A half-plane cut off by a disk needs no box: the disk's.
  Problem q;
  q.h0 = 0.1;
  q.geometry = csg(CsgOp::kIntersection,
                   {Shape{HalfPlane{{0, 1}, 0}, "", ""}, Shape{Circle{{0, 0}, 1}, "", ""}});
  EXPECT_EQ(error_field(q), "");
  EXPECT_EQ(compile_problem(q).bbox.max.x, 1.0);
}

TEST(CompileProblem, GivenBoxIsClippedToTheGeometry) {
  Problem p = testing::benchmark_problem("G1", 0.1);
  p.bbox = Box{{-5, 0.25}, {0.5, 5}};
  const CompiledProblem c = compile_problem(p);
  EXPECT_EQ(c.bbox.min.x, -1.0);
  EXPECT_EQ(c.bbox.min.y, 0.25);
  EXPECT_EQ(c.bbox.max.x, 0.5);
  EXPECT_EQ(c.bbox.max.y, 1.0);
  // A box that misses the geometry.
  p.bbox = Box{{5, 5}, {6, 6}};
  EXPECT_EQ(error_field(p), "bbox");
}

TEST(CompileProblem, FixedPointOutsideNamesItsIndex) {
  Problem p = testing::benchmark_problem("G1", 0.1);
  p.fixed_points = {{0, 0}, {1, 0}, {0.5, 0.5}, {1.2, 0}};
  EXPECT_EQ(error_field(p), "fixed_points[3]");
  try {
    compile_problem(p);
  } catch (const Error& e) {
    EXPECT_NE(e.detail().find("geps"), std::string::npos) << e.detail();
  }
  // On the boundary, or outside by less than geps * h0, is allowed; just beyond is not.
  const double geps = p.params.geps * p.h0;
  p.fixed_points = {{1, 0}, {0, -1 - 0.5 * geps}};
  EXPECT_EQ(error_field(p), "");
  p.fixed_points = {{0, 0}, {0, -1 - 2 * geps}};
  EXPECT_EQ(error_field(p), "fixed_points[1]");
  // Inside the hole of G2 is outside the domain.
  Problem g2 = testing::benchmark_problem("G2", 0.1);
  g2.fixed_points = {{0.9, 0.9}, {0.1, 0.1}};
  EXPECT_EQ(error_field(g2), "fixed_points[1]");
}

TEST(CompileProblem, EmptyIntersectionIsAnEmptyGeometry) {
  Problem p;
  p.h0 = 0.1;
  p.geometry = csg(CsgOp::kIntersection,
                   {Shape{Circle{{0, 0}, 1}, "", ""}, Shape{Rectangle{{3, 3}, {4, 4}}, "", ""}});
  EXPECT_EQ(error_field(p), "geometry");
  // Empty even with a box given.
  p.bbox = Box{{-10, -10}, {10, 10}};
  EXPECT_EQ(error_field(p), "geometry");
}

TEST(CompileProblem, FixedPointsGivenFirstThenCornersWithoutDuplicates) {
  Problem p = testing::benchmark_problem("G2", 0.1);
  p.fixed_points = {{0.75, 0}, {1, 1}, {0.75, 0}};  // a corner given, and a repeat
  const CompiledProblem c = compile_problem(p);
  ASSERT_EQ(c.fixed_points.size(), 5u);  // (0.75, 0), (1, 1), then the 3 other corners
  EXPECT_TRUE(c.fixed_points[0] == (Vec2{0.75, 0}));
  EXPECT_TRUE(c.fixed_points[1] == (Vec2{1, 1}));
  for (size_t i = 2; i < 5; ++i) {
    EXPECT_EQ(std::fabs(c.fixed_points[i].x), 1.0);
    EXPECT_EQ(std::fabs(c.fixed_points[i].y), 1.0);
    EXPECT_FALSE(c.fixed_points[i] == (Vec2{1, 1}));
  }
  // Without auto_corners only the given points.
  p.auto_corners = false;
  EXPECT_EQ(compile_problem(p).fixed_points.size(), 2u);
  // G3: its 10 vertices, exactly.
  const CompiledProblem g3 = compile_problem(testing::benchmark_problem("G3", 0.1));
  EXPECT_EQ(g3.fixed_points.size(), 10u);
  // G1, G4: smooth, none.
  EXPECT_TRUE(compile_problem(testing::benchmark_problem("G1", 0.1)).fixed_points.empty());
  EXPECT_TRUE(compile_problem(testing::benchmark_problem("G4", 0.1)).fixed_points.empty());
}

TEST(CompileProblem, CopiesParametersAndSeed) {
  Problem p = testing::benchmark_problem("G5", 0.07);
  p.seed = 1234;
  p.params.max_iterations = 17;
  p.params.cleanup = false;
  const CompiledProblem c = compile_problem(p);
  EXPECT_EQ(c.h0, 0.07);
  EXPECT_EQ(c.seed, 1234u);
  EXPECT_EQ(c.params.max_iterations, 17);
  EXPECT_FALSE(c.params.cleanup);
  EXPECT_EQ(c.size.terms.size(), 1u);
  EXPECT_FALSE(c.size.uniform());
  EXPECT_EQ(c.geometry.primitives.size(), 2u);
}

}  // namespace
}  // namespace meshd
