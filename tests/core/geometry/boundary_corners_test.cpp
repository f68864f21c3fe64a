// Boundary corners (compiled_problem.h): polygon and rectangle vertices on the final boundary, and
// the crossings of two primitives' boundaries (boundary_crossings.h) for every pair of curves a
// request can form: segment and line with each other, with a circle and with an ellipse; circle
// with circle and with an ellipse; ellipse with ellipse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/boundary_crossings.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

using testing::circle;
using testing::csg;
using testing::ellipse;
using testing::half_plane;
using testing::rectangle;
using testing::transformed;

constexpr double kPi = std::numbers::pi;

// ---- Boundary corners ---------------------------------------------------------------------------

std::vector<Vec2> corners_of(const Shape& s) {
  const Program p = compile_geometry(s);
  return boundary_corners(p, program_bounds(p));
}

bool contains(const std::vector<Vec2>& pts, Vec2 q, double tol = 1e-12) {
  return std::any_of(pts.begin(), pts.end(), [&](Vec2 p) { return norm(p - q) <= tol; });
}

TEST(BoundaryCorners, SquareMinusDiskHasItsFourCorners) {
  const auto c =
      corners_of(csg(CsgOp::kDifference, {rectangle({-1, -1}, {1, 1}), circle({0, 0}, 0.5)}));
  ASSERT_EQ(c.size(), 4u);
  for (Vec2 q : {Vec2{-1, -1}, Vec2{1, -1}, Vec2{1, 1}, Vec2{-1, 1}}) EXPECT_TRUE(contains(c, q));
}

TEST(BoundaryCorners, RectangleInsideAUnionContributesNone) {
  const auto c =
      corners_of(csg(CsgOp::kUnion, {rectangle({-1, -1}, {1, 1}),
                                     rectangle({-0.5, -0.5}, {0.5, 0.5}), circle({0, 0}, 0.2)}));
  ASSERT_EQ(c.size(), 4u);
  for (Vec2 q : {Vec2{-1, -1}, Vec2{1, -1}, Vec2{1, 1}, Vec2{-1, 1}}) EXPECT_TRUE(contains(c, q));
  // Overlapping rectangles: the corners outside the other one survive, and the two points
  // where their sides cross become the union's concave corners.
  const auto l =
      corners_of(csg(CsgOp::kUnion, {rectangle({0, 0}, {2, 1}), rectangle({1, -1}, {3, 0.5})}));
  EXPECT_EQ(l.size(), 8u);
  EXPECT_FALSE(contains(l, {2, 0}));    // inside the second
  EXPECT_FALSE(contains(l, {1, 0.5}));  // inside the first
  EXPECT_TRUE(contains(l, {2, 0.5}));
  EXPECT_TRUE(contains(l, {1, 0}));
  // A rectangular hole: its corners are on the boundary too.
  const auto h = corners_of(
      csg(CsgOp::kDifference, {rectangle({-2, -2}, {2, 2}), rectangle({-1, -1}, {1, 1})}));
  EXPECT_EQ(h.size(), 8u);
}

TEST(BoundaryCorners, PolygonVerticesTransformed) {
  const std::vector<Vec2> g3 = {{-0.4, -0.5}, {0.4, -0.2}, {0.4, -0.7}, {1.5, -0.4}, {0.9, 0.1},
                                {1.6, 0.8},   {0.5, 0.5},  {0.2, 1},    {0.1, 0.4},  {-0.7, 0.7}};
  const auto c = corners_of(Shape{Polygon{g3}, "", ""});
  ASSERT_EQ(c.size(), g3.size());
  for (Vec2 v : g3) EXPECT_TRUE(contains(c, v));
  // Under a similarity, the corners are the transformed vertices.
  const Similarity t{1.5, 0.4, {2, -1}};
  const auto ct = corners_of(transformed(Shape{Polygon{g3}, "", ""}, t.scale, t.angle, t.offset));
  ASSERT_EQ(ct.size(), g3.size());
  for (Vec2 v : g3) EXPECT_TRUE(contains(ct, apply(t, v), 1e-12));
  // A rotated rectangle's corners.
  const auto cr = corners_of(transformed(rectangle({0, 0}, {2, 1}), 1, kPi / 5, {0, 0}));
  EXPECT_EQ(cr.size(), 4u);
}

TEST(BoundaryCorners, FinelySampledCurveHasNoCornersButItsSharpVerticesDo) {
  std::vector<Vec2> circle_samples, half_disk;
  for (int k = 0; k < 720; ++k) {
    const double a = 2 * kPi * k / 720;
    circle_samples.push_back({std::cos(a), std::sin(a)});
  }
  EXPECT_TRUE(corners_of(Shape{Polygon{circle_samples}, "", ""}).empty());
  // A half disk: the arc turns by 0.5 degrees per vertex, the diameter's ends by 90.
  for (int k = 0; k <= 360; ++k) {
    const double a = kPi * k / 360;
    half_disk.push_back({std::cos(a), std::sin(a)});
  }
  const auto c = corners_of(Shape{Polygon{half_disk}, "", ""});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(contains(c, half_disk.front()));
  EXPECT_TRUE(contains(c, half_disk.back()));
}

// ---- Crossings of two primitives ---------------------------------------------------------------

// Every corner lies on the boundary of the whole shape and of at least two of its primitives.
void expect_on_two_boundaries(const Shape& s, const std::vector<Vec2>& corners) {
  const Program p = compile_geometry(s);
  for (Vec2 c : corners) {
    EXPECT_LE(std::fabs(eval_sdf(p.view(), c)), 1e-12) << c.x << " " << c.y;
    int on = 0;
    for (const Instruction& ins : p.code) {
      if (ins.primitive < 0) continue;
      on += std::fabs(sdf_primitive(p.view(), ins, c)) <= 1e-12;
    }
    EXPECT_GE(on, 1) << c.x << " " << c.y;
  }
}

TEST(BoundaryCorners, LinesMeetAtTheChannelsCorners) {
  // The airfoil example's channel: four half-planes, no primitive with a corner of its own.
  const Shape channel =
      csg(CsgOp::kIntersection, {half_plane({-1, 0}, 1.5), half_plane({1, 0}, 3.5),
                                 half_plane({0, -1}, 1), half_plane({0, 1}, 1)});
  // Unbounded primitives are clipped to the problem's box, which a request gives (bbox).
  const auto c = boundary_corners(compile_geometry(channel), Box{{-1.5, -1}, {3.5, 1}});
  ASSERT_EQ(c.size(), 4u);
  for (Vec2 q : {Vec2{-1.5, -1}, Vec2{3.5, -1}, Vec2{3.5, 1}, Vec2{-1.5, 1}})
    EXPECT_TRUE(contains(c, q)) << q.x << " " << q.y;
}

TEST(BoundaryCorners, LineCutsACircle) {
  // A disk cut by x <= 0.5: two convex corners at (0.5, +-sqrt(0.75)), to the last bits.
  const Shape d = csg(CsgOp::kIntersection, {circle({0, 0}, 1), half_plane({1, 0}, 0.5)});
  const auto c = corners_of(d);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_TRUE(contains(c, {0.5, std::sqrt(0.75)}, 1e-15));
  EXPECT_TRUE(contains(c, {0.5, -std::sqrt(0.75)}, 1e-15));
  // The same cut as a hole: a disk minus a slot makes concave corners where the slot's sides
  // leave the circle.
  const Shape slotted =
      csg(CsgOp::kDifference, {circle({0, 0}, 1), rectangle({0.6, -0.1}, {2, 0.1})});
  const auto s = corners_of(slotted);
  ASSERT_EQ(s.size(), 4u);  // two crossings, two slot corners inside the disk
  EXPECT_TRUE(contains(s, {std::sqrt(0.99), 0.1}, 1e-15));
  EXPECT_TRUE(contains(s, {0.6, -0.1}));
  expect_on_two_boundaries(slotted, s);
}

TEST(BoundaryCorners, CirclesCrossInAUnionAndADifference) {
  // Two unit disks 1 apart cross at (0.5, +-sqrt(0.75)): concave corners of their union, convex
  // ones of their difference (a crescent) and of their intersection (a lens).
  for (CsgOp op : {CsgOp::kUnion, CsgOp::kDifference, CsgOp::kIntersection}) {
    const Shape s = csg(op, {circle({0, 0}, 1), circle({1, 0}, 1)});
    const auto c = corners_of(s);
    ASSERT_EQ(c.size(), 2u) << static_cast<int>(op);
    EXPECT_TRUE(contains(c, {0.5, std::sqrt(0.75)}, 1e-15));
    EXPECT_TRUE(contains(c, {0.5, -std::sqrt(0.75)}, 1e-15));
  }
  // Tangent disks touch without crossing: the boundary does not turn there.
  EXPECT_TRUE(corners_of(csg(CsgOp::kUnion, {circle({0, 0}, 1), circle({2, 0}, 1)})).empty());
  // A disk inside another: no crossing, no corner.
  EXPECT_TRUE(
      corners_of(csg(CsgOp::kDifference, {circle({0, 0}, 1), circle({0, 0}, 0.5)})).empty());
}

TEST(BoundaryCorners, EllipseCrossesLinesCirclesAndEllipses) {
  // Ellipse (x/2)^2 + y^2 <= 1 cut by x <= 1: corners at (1, +-sqrt(0.75)).
  const auto cut =
      corners_of(csg(CsgOp::kIntersection, {ellipse({0, 0}, 2, 1), half_plane({1, 0}, 1)}));
  ASSERT_EQ(cut.size(), 2u);
  EXPECT_TRUE(contains(cut, {1, std::sqrt(0.75)}, 1e-14));
  // With the circle x^2 + y^2 = 2: x^2/4 + 2 - x^2 = 1, so x^2 = 4/3, y^2 = 2/3.
  const Shape ec = csg(CsgOp::kUnion, {ellipse({0, 0}, 2, 1), circle({0, 0}, std::sqrt(2.0))});
  const auto c = corners_of(ec);
  ASSERT_EQ(c.size(), 4u);
  for (Vec2 q : c) {
    EXPECT_NEAR(std::fabs(q.x), std::sqrt(4.0 / 3), 1e-13);
    EXPECT_NEAR(std::fabs(q.y), std::sqrt(2.0 / 3), 1e-13);
  }
  // With the same ellipse turned by 90 degrees: x^2/4 + y^2 = 1 = x^2 + y^2/4 at |x| = |y| =
  // sqrt(4/5).
  const Shape cross = csg(CsgOp::kUnion, {ellipse({0, 0}, 2, 1),
                                          transformed(ellipse({0, 0}, 2, 1), 1, kPi / 2, {0, 0})});
  const auto e = corners_of(cross);
  ASSERT_EQ(e.size(), 4u);
  for (Vec2 q : e) {
    EXPECT_NEAR(std::fabs(q.x), std::sqrt(0.8), 1e-13);
    EXPECT_NEAR(std::fabs(q.y), std::sqrt(0.8), 1e-13);
  }
  expect_on_two_boundaries(cross, e);
}

TEST(BoundaryCorners, GearHasItsToothRootsAndKeywayCorners) {
  // The gear example: 12 teeth (0.95..1.2 by +-0.09) on a unit disk, minus a bore of radius 0.3
  // with a keyway (0.2..0.38 by +-0.06). Each tooth: 2 outer corners and 2 roots where its sides
  // leave the circle; the bore: the keyway's 2 outer corners and 2 crossings with the circle.
  std::vector<Shape> rim = {circle({0, 0}, 1)};
  for (int k = 0; k < 12; ++k)
    rim.push_back(transformed(rectangle({0.95, -0.09}, {1.2, 0.09}), 1, k * kPi / 6, {0, 0}));
  const Shape gear =
      csg(CsgOp::kDifference,
          {csg(CsgOp::kUnion, rim),
           csg(CsgOp::kUnion, {circle({0, 0}, 0.3), rectangle({0.2, -0.06}, {0.38, 0.06})})});
  const auto c = corners_of(gear);
  EXPECT_EQ(c.size(), 12u * 4 + 4);
  EXPECT_TRUE(contains(c, {std::sqrt(1 - 0.09 * 0.09), 0.09}, 1e-15));
  EXPECT_TRUE(contains(c, {std::sqrt(0.09 - 0.06 * 0.06), -0.06}, 1e-15));
  expect_on_two_boundaries(gear, c);
}

TEST(BoundaryCrossings, CrossingsOffTheFinalBoundaryAreFoundButNotCorners) {
  // Three disks in a row: the outer two cross at (0.5, +-sqrt(0.75)), inside the middle one.
  const Shape s = csg(CsgOp::kUnion, {circle({0, 0}, 1), circle({0.5, 0}, 1), circle({1, 0}, 1)});
  const Program p = compile_geometry(s);
  const auto all = boundary_crossings(p, program_bounds(p));
  EXPECT_EQ(all.size(), 6u);
  const auto c = boundary_corners(p, program_bounds(p));
  EXPECT_EQ(c.size(), 4u);
  EXPECT_FALSE(contains(c, {0.5, std::sqrt(0.75)}, 1e-12));
  EXPECT_TRUE(contains(c, {0.25, std::sqrt(1 - 0.25 * 0.25)}, 1e-15));
}

TEST(BoundaryCorners, TooManyCrossingsAreRefusedNamingTheGeometry) {
  // A grid of 80 thin horizontal and 80 thin vertical bars: each pair's union has 4 concave
  // corners, 25,600 in all, past kMaxCrossingCorners.
  std::vector<Shape> bars;
  for (int k = 0; k < 80; ++k) {
    bars.push_back(rectangle({0, k + 0.4}, {80, k + 0.6}));
    bars.push_back(rectangle({k + 0.4, 0}, {k + 0.6, 80}));
  }
  const Program p = compile_geometry(csg(CsgOp::kUnion, bars));
  try {
    boundary_corners(p, program_bounds(p));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "geometry");
    EXPECT_NE(std::string(e.what()).find("at most 20000"), std::string::npos) << e.what();
  }
}

TEST(BoundaryCorners, ManyPolygonCornersAreNoCrossings) {
  // A jagged ring of 30,000 vertices (radius 1 and 0.99 in turn, as a raw coastline zigzags)
  // inside a rectangle: every vertex a corner, past kMaxCrossingCorners, and no crossing.
  constexpr int kVertices = 30000;
  Polygon ring;
  for (int k = 0; k < kVertices; ++k) {
    const double a = 2 * kPi * k / kVertices, r = k % 2 == 0 ? 1.0 : 0.99;
    ring.vertices.push_back({r * std::cos(a), r * std::sin(a)});
  }
  const Shape sea = csg(CsgOp::kDifference,
                        {rectangle({-2, -2}, {2, 2}), Shape{std::move(ring), "", ""}});
  const auto c = corners_of(sea);
  EXPECT_EQ(c.size(), static_cast<size_t>(kVertices) + 4);
}

}  // namespace
}  // namespace meshd
