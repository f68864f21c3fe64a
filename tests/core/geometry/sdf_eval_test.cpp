// The signed-distance evaluator (sdf_eval.cuh) through compile_geometry: every primitive against
// exact or brute-force distances, the CSG operations, transforms folded into the primitives, and
// the owner output that tags boundary edges.
#include "core/geometry/sdf_eval.cuh"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/geometry/compile.h"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

constexpr double kPi = std::numbers::pi;

double sdf(const Shape& shape, Vec2 p) {
  const Program program = compile_geometry(shape);
  return eval_sdf(program.view(), p);
}

using testing::csg;
using testing::transformed;

// ---- Brute-force references -------------------------------------------------------------------

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
  return norm(p - (a + t * e));
}

// Winding number (not the evaluator's crossing number): nonzero inside a simple polygon.
int winding_number(Vec2 p, const std::vector<Vec2>& v) {
  int w = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec2 a = v[i], b = v[(i + 1) % v.size()];
    const double side = cross(b - a, p - a);
    if (a.y <= p.y) {
      if (b.y > p.y && side > 0) ++w;
    } else if (b.y <= p.y && side < 0) {
      --w;
    }
  }
  return w;
}

double polygon_reference(const std::vector<Vec2>& v, Vec2 p) {
  double d = INFINITY;
  for (size_t i = 0; i < v.size(); ++i)
    d = std::min(d, segment_distance(p, v[i], v[(i + 1) % v.size()]));
  return winding_number(p, v) != 0 ? -d : d;
}

// Distance from q to the ellipse x = a cos t, y = b sin t (axis-aligned, centred at 0): dense
// sampling of t, then every sampled local minimum refined by golden-section search. Independent
// of the evaluator's root finding; accurate to a few ulps of the semi axes.
double ellipse_boundary_distance(double a, double b, Vec2 q) {
  constexpr int kSamples = 2048;
  auto f = [&](double t) {
    const double dx = a * std::cos(t) - q.x, dy = b * std::sin(t) - q.y;
    return dx * dx + dy * dy;
  };
  const double dt = 2 * kPi / kSamples;
  std::vector<double> sampled(kSamples);
  for (int k = 0; k < kSamples; ++k) sampled[k] = f(k * dt);
  double best = INFINITY;
  for (int k = 0; k < kSamples; ++k) {
    const double prev = sampled[(k + kSamples - 1) % kSamples], next = sampled[(k + 1) % kSamples];
    if (sampled[k] > prev || sampled[k] > next) continue;
    double lo = (k - 1) * dt, hi = (k + 1) * dt;
    const double g = (std::sqrt(5.0) - 1) / 2;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = f(x1), f2 = f(x2);
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(x2);
      }
    }
    best = std::min({best, sampled[k], f1, f2});
  }
  return std::sqrt(best);
}

double ellipse_reference(double a, double b, Vec2 q) {
  const double d = ellipse_boundary_distance(a, b, q);
  return (q.x / a) * (q.x / a) + (q.y / b) * (q.y / b) < 1.0 ? -d : d;
}

// ---- Circle -------------------------------------------------------------------------------------

TEST(SdfEval, CircleExactDistances) {
  const Shape c{Circle{{1, -2}, 0.5}, "", ""};
  EXPECT_DOUBLE_EQ(sdf(c, {1, -2}), -0.5);      // centre
  EXPECT_DOUBLE_EQ(sdf(c, {1.25, -2}), -0.25);  // inside
  EXPECT_DOUBLE_EQ(sdf(c, {1, -1.5}), 0.0);     // on the boundary
  EXPECT_DOUBLE_EQ(sdf(c, {4, 2}), 4.5);        // outside: 3-4-5 triangle
  EXPECT_NEAR(sdf(c, {1 - 0.3, -2 - 0.4}), 0.0, 1e-15);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    EXPECT_NEAR(sdf(c, p), std::hypot(p.x - 1, p.y + 2) - 0.5, 1e-14);
  }
}

// ---- Rectangle ----------------------------------------------------------------------------------

TEST(SdfEval, RectangleInsideSidesAndCorners) {
  const Shape r{Rectangle{{-1, 0}, {2, 1}}, "", ""};
  // Inside: minus the distance to the nearest side.
  EXPECT_DOUBLE_EQ(sdf(r, {0.5, 0.5}), -0.5);
  EXPECT_NEAR(sdf(r, {1.9, 0.5}), -0.1, 1e-15);
  EXPECT_NEAR(sdf(r, {-0.8, 0.3}), -0.2, 1e-15);
  // Outside a side: the distance to that side.
  EXPECT_DOUBLE_EQ(sdf(r, {0.5, 3}), 2.0);
  EXPECT_DOUBLE_EQ(sdf(r, {-4, 0.5}), 3.0);
  // Outside a corner: the distance to the corner point, not to either side's line.
  EXPECT_DOUBLE_EQ(sdf(r, {5, 5}), 5.0);    // corner (2, 1): (3, 4)
  EXPECT_DOUBLE_EQ(sdf(r, {-4, -4}), 5.0);  // corner (-1, 0): (-3, -4)
  EXPECT_DOUBLE_EQ(sdf(r, {2.3, -0.4}), 0.5);
  EXPECT_DOUBLE_EQ(sdf(r, {-1.6, 1.8}), 1.0);
  // On the boundary and at a corner.
  EXPECT_DOUBLE_EQ(sdf(r, {2, 0.5}), 0.0);
  EXPECT_DOUBLE_EQ(sdf(r, {-1, 1}), 0.0);

  const std::vector<Vec2> corners = {{-1, 0}, {2, 0}, {2, 1}, {-1, 1}};
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-4, 4);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    EXPECT_NEAR(sdf(r, p), polygon_reference(corners, p), 1e-14) << p.x << " " << p.y;
  }
}

TEST(SdfEval, RotatedRectangleMatchesItsCornerPolygon) {
  // [0,2] x [0,1] rotated by 30 degrees about the origin, scaled by 1.5, moved by (1, -1).
  const double angle = kPi / 6, scale = 1.5;
  const Vec2 offset{1, -1};
  const Shape r = transformed(Shape{Rectangle{{0, 0}, {2, 1}}, "", ""}, scale, angle, offset);
  std::vector<Vec2> corners;
  for (Vec2 v : {Vec2{0, 0}, Vec2{2, 0}, Vec2{2, 1}, Vec2{0, 1}})
    corners.push_back(apply({scale, angle, offset}, v));
  const Program program = compile_geometry(r);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-4, 6);
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    EXPECT_NEAR(eval_sdf(program.view(), p), polygon_reference(corners, p), 1e-13);
  }
  // Beyond a rotated corner along its diagonal: the distance to the corner.
  const Vec2 c2 = corners[2], centre = 0.5 * (corners[0] + corners[2]);
  const Vec2 diag = (1.0 / norm(c2 - centre)) * (c2 - centre);
  EXPECT_NEAR(eval_sdf(program.view(), c2 + 0.7 * diag), 0.7, 1e-14);
  EXPECT_NEAR(eval_sdf(program.view(), centre), -0.75, 1e-14);  // half the short side, scaled
}

// ---- Ellipse ------------------------------------------------------------------------------------

struct EllipseCase {
  double a, b;
};

std::string ellipse_case_name(const ::testing::TestParamInfo<EllipseCase>& param) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "a%g_b%g", param.param.a, param.param.b);
  std::string name = buf;
  std::replace(name.begin(), name.end(), '.', '_');
  return name;
}

// Query points: uniform over a box around the ellipse, on and near both axes (`offsets` are
// relative to the semi axes), at distances `centre_radii` (relative to the smaller semi axis)
// from the centre, and close to the boundary on both sides.
std::vector<Vec2> ellipse_queries(double a, double b, uint64_t seed,
                                  const std::vector<double>& offsets,
                                  const std::vector<double>& centre_radii) {
  std::vector<Vec2> q;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.6, 1.6), unit(0, 1), ang(0, 2 * kPi);
  for (int i = 0; i < 300; ++i) q.push_back({u(rng) * a, u(rng) * b});
  for (double off : offsets) {
    for (double s :
         {-1.5, -1.0, -0.999, -0.9, -0.5, -0.1, 0.0, 0.3, 0.7, 0.95, 0.999, 1.0, 1.001, 1.2, 2.0}) {
      q.push_back({s * a, off * b});
      q.push_back({s * a, -off * b});
      q.push_back({off * a, s * b});
      q.push_back({-off * a, s * b});
    }
  }
  for (double r : centre_radii) {
    for (int i = 0; i < 20; ++i) {
      const double t = ang(rng), rr = r * std::min(a, b) * (1 + unit(rng));
      q.push_back({rr * std::cos(t), rr * std::sin(t)});
    }
  }
  for (int i = 0; i < 200; ++i) {  // near the boundary, inside and outside
    const double t = ang(rng), s = 1 + (unit(rng) - 0.5) * 1e-2;
    q.push_back({s * a * std::cos(t), s * b * std::sin(t)});
  }
  return q;
}

// Counts (and reports the first few of) the queries where the evaluator is off by more than
// 1e-9 relative (plus a few ulps of the semi axes, for points on the boundary).
int ellipse_mismatches(double a, double b, const std::vector<Vec2>& queries) {
  const Program program = compile_geometry(Shape{Ellipse{{0, 0}, a, b}, "", ""});
  int failures = 0;
  for (Vec2 p : queries) {
    const double want = ellipse_reference(a, b, p);
    const double got = eval_sdf(program.view(), p);
    const double tol = 1e-9 * std::fabs(want) + 1e-13 * std::max(a, b);
    if (!(std::fabs(got - want) <= tol) && ++failures <= 5) {
      ADD_FAILURE() << "ellipse " << a << ":" << b << " at (" << p.x << ", " << p.y << "): got "
                    << got << ", brute force " << want << ", error " << got - want;
    }
  }
  return failures;
}

class EllipseSdf : public ::testing::TestWithParam<EllipseCase> {};

TEST_P(EllipseSdf, MatchesBruteForceClosestPoint) {
  const auto [a, b] = GetParam();
  const auto queries = ellipse_queries(a, b, static_cast<uint64_t>(a * 1000 + b),
                                       {0.0, 1e-4, 1e-3, 1e-2, 0.1}, {1e-2, 0.1, 0.3});
  EXPECT_EQ(ellipse_mismatches(a, b, queries), 0);
}

// Regression: the solve once ran in s = t - 1, and s + 1 cancelled near the major axis (2:1
// ellipse at (2.01, 1e-16) gave 0.807 instead of 0.01) and near the centre.
TEST_P(EllipseSdf, NearTheMajorAxisAndTheCentre) {
  const auto [a, b] = GetParam();
  const auto queries = ellipse_queries(a, b, static_cast<uint64_t>(a * 1000 + b) + 1,
                                       {1e-17, 1e-16, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-5},
                                       {1e-9, 1e-7, 1e-5, 1e-3});
  EXPECT_EQ(ellipse_mismatches(a, b, queries), 0);
}

INSTANTIATE_TEST_SUITE_P(Shapes, EllipseSdf,
                         ::testing::Values(EllipseCase{1, 1}, EllipseCase{2, 1}, EllipseCase{1, 2},
                                           EllipseCase{10, 1}, EllipseCase{1, 10},
                                           EllipseCase{0.3, 0.05}),
                         ellipse_case_name);

// Regression: the same through a rotation, where the local coordinate across the major axis is
// rounding noise (1e-17 instead of 0), outside the ellipse too, where nodes are projected.
// Example: the 2:1 ellipse rotated by 0.3 about (0.3, -0.7), at centre + 2.5 * major axis.
TEST(SdfEval, RotatedEllipseOnItsMajorAxis) {
  const Vec2 centre{0.3, -0.7};
  int failures = 0;
  for (double angle : {0.3, 1.0, kPi / 3, 2.5, -0.8}) {
    const Program program =
        compile_geometry(transformed(Shape{Ellipse{{0, 0}, 2, 1}, "", ""}, 1, angle, centre));
    const Vec2 major{std::cos(angle), std::sin(angle)};
    for (double s : {-2.5, -1.9, -1.0, -0.3, 0.2, 0.5, 1.0, 1.3, 1.7, 1.99, 2.01, 2.5, 3.0}) {
      // Exact on the axis: |s| - 2 from the vertex on; inside the evolute (|s| < (a^2 - b^2) / a
      // = 1.5) the distance to the closest point (4s/3, sqrt(1 - 4s^2/9)), sqrt(1 - s^2/3).
      const double want = std::fabs(s) < 1.5 ? -std::sqrt(1 - s * s / 3) : std::fabs(s) - 2;
      const double got = eval_sdf(program.view(), centre + s * major);
      if (!(std::fabs(got - want) <= 1e-9)) {
        ++failures;
        ADD_FAILURE() << "angle " << angle << ", s = " << s << ": got " << got << ", want " << want;
      }
    }
  }
  EXPECT_EQ(failures, 0);
}

TEST(SdfEval, EllipseExactValuesOnItsAxes) {
  const Shape e{Ellipse{{1, 2}, 2, 1}, "", ""};
  EXPECT_DOUBLE_EQ(sdf(e, {1, 2}), -1.0);  // centre: the nearer vertex (0, +-1)
  EXPECT_DOUBLE_EQ(sdf(e, {5, 2}), 2.0);   // beyond the major vertex (3, 2)
  EXPECT_DOUBLE_EQ(sdf(e, {1, 5}), 2.0);   // beyond the minor vertex (1, 3)
  EXPECT_DOUBLE_EQ(sdf(e, {3, 2}), 0.0);
  EXPECT_DOUBLE_EQ(sdf(e, {1, 1}), 0.0);
}

TEST(SdfEval, RotatedTranslatedEllipse) {
  const double a = 3, b = 0.5, angle = 0.7, scale = 1.3;
  const Vec2 offset{-2, 0.5};
  const Shape e = transformed(Shape{Ellipse{{0.2, -0.1}, a, b}, "", ""}, scale, angle, offset);
  const Program program = compile_geometry(e);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-6, 4);
  for (int i = 0; i < 300; ++i) {
    const Vec2 p{u(rng), u(rng)};
    // Untransformed frame: q = R(-angle) (p - offset) / scale, relative to the ellipse centre.
    const Vec2 w = (1.0 / scale) * (p - offset);
    const Vec2 q{std::cos(angle) * w.x + std::sin(angle) * w.y - 0.2,
                 -std::sin(angle) * w.x + std::cos(angle) * w.y + 0.1};
    const double want = scale * ellipse_reference(a, b, q);
    EXPECT_NEAR(eval_sdf(program.view(), p), want, 1e-9 * std::fabs(want) + 1e-12);
  }
}

// ---- Half-plane ---------------------------------------------------------------------------------

TEST(SdfEval, HalfPlaneWithNonUnitNormal) {
  // 3x + 4y <= 10: the boundary is 2 units from the origin along (0.6, 0.8).
  const Shape h{HalfPlane{{3, 4}, 10}, "", ""};
  EXPECT_DOUBLE_EQ(sdf(h, {0, 0}), -2.0);
  EXPECT_DOUBLE_EQ(sdf(h, {1.2, 1.6}), 0.0);
  EXPECT_DOUBLE_EQ(sdf(h, {1.8, 2.4}), 1.0);
  EXPECT_NEAR(sdf(h, {1.2 - 0.8 * 5, 1.6 + 0.6 * 5}), 0.0, 1e-14);  // along the boundary
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 200; ++i) {
    const Vec2 p{u(rng), u(rng)};
    EXPECT_NEAR(sdf(h, p), (3 * p.x + 4 * p.y - 10) / 5, 1e-13);
  }
  // A tiny normal is normalised the same way.
  EXPECT_NEAR(sdf(Shape{HalfPlane{{0, 1e-3}, 2e-3}, "", ""}, {7, 5}), 3.0, 1e-12);
}

// ---- Polygon ------------------------------------------------------------------------------------

std::vector<Vec2> g3_polygon() {
  return {{-0.4, -0.5}, {0.4, -0.2}, {0.4, -0.7}, {1.5, -0.4}, {0.9, 0.1},
          {1.6, 0.8},   {0.5, 0.5},  {0.2, 1},    {0.1, 0.4},  {-0.7, 0.7}};
}

std::vector<Vec2> star(int tips) {
  std::vector<Vec2> v;
  for (int i = 0; i < 2 * tips; ++i) {
    const double r = i % 2 == 0 ? 1.0 : 0.35, t = kPi * i / tips;
    v.push_back({r * std::cos(t), r * std::sin(t)});
  }
  return v;
}

std::vector<Vec2> hexagon() {
  std::vector<Vec2> v;
  for (int i = 0; i < 6; ++i) v.push_back({std::cos(kPi * i / 3), std::sin(kPi * i / 3)});
  return v;
}

void expect_polygon_matches(const std::vector<Vec2>& vertices, uint64_t seed) {
  const Program program = compile_geometry(Shape{Polygon{vertices}, "", ""});
  Box box{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
  for (Vec2 v : vertices) {
    box.min = {std::min(box.min.x, v.x), std::min(box.min.y, v.y)};
    box.max = {std::max(box.max.x, v.x), std::max(box.max.y, v.y)};
  }
  std::vector<Vec2> queries;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(box.min.x - 0.5, box.max.x + 0.5),
      uy(box.min.y - 0.5, box.max.y + 0.5);
  for (int i = 0; i < 3000; ++i) queries.push_back({ux(rng), uy(rng)});
  // Rays through vertices are where crossing counts go wrong: query at every vertex's height.
  for (Vec2 v : vertices)
    for (int i = 0; i < 40; ++i) queries.push_back({ux(rng), v.y});
  int inside = 0;
  for (Vec2 p : queries) {
    const double want = polygon_reference(vertices, p);
    if (want == 0.0) continue;  // exactly on an edge: either sign of zero is right
    const double got = eval_sdf(program.view(), p);
    inside += want < 0;
    ASSERT_NEAR(got, want, 1e-14) << "at (" << p.x << ", " << p.y << ")";
  }
  EXPECT_GT(inside, 100);  // both signs were exercised
}

TEST(SdfEval, PolygonConvexBothOrientations) {
  std::vector<Vec2> v = hexagon();
  expect_polygon_matches(v, 6);
  std::reverse(v.begin(), v.end());
  expect_polygon_matches(v, 7);
  // A triangle with a horizontal edge.
  expect_polygon_matches({{0, 0}, {2, 0}, {0.5, 1.5}}, 8);
}

TEST(SdfEval, PolygonNonConvexBothOrientations) {
  std::vector<Vec2> v = g3_polygon();
  expect_polygon_matches(v, 9);
  std::reverse(v.begin(), v.end());
  expect_polygon_matches(v, 10);
  v = star(7);
  expect_polygon_matches(v, 11);
  std::reverse(v.begin(), v.end());
  expect_polygon_matches(v, 12);
}

TEST(SdfEval, PolygonKnownValues) {
  // Unit square as a polygon: the same distances as the box, corners included.
  const Shape sq{Polygon{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}, "", ""};
  EXPECT_DOUBLE_EQ(sdf(sq, {0.5, 0.5}), -0.5);
  EXPECT_DOUBLE_EQ(sdf(sq, {0.5, 0.25}), -0.25);
  EXPECT_DOUBLE_EQ(sdf(sq, {4, 5}), 5.0);
  EXPECT_DOUBLE_EQ(sdf(sq, {0.5, -2}), 2.0);
  EXPECT_DOUBLE_EQ(sdf(sq, {1, 0.5}), 0.0);
  // G3's notch below its reflex vertex (0.4, -0.2): 0.1 from the vertical edge x = 0.4, outside
  // on its left, inside on its right.
  const Shape g3{Polygon{g3_polygon()}, "", ""};
  EXPECT_NEAR(sdf(g3, {0.3, -0.35}), 0.1, 1e-15);
  EXPECT_NEAR(sdf(g3, {0.5, -0.35}), -0.1, 1e-15);
  // Above the vertex: nearest to the edge (-0.4, -0.5) -> (0.4, -0.2), inside.
  EXPECT_NEAR(sdf(g3, {0.3, -0.1}), -0.11 / std::hypot(0.8, 0.3), 1e-14);
}

// ---- CSG ----------------------------------------------------------------------------------------

TEST(SdfEval, UnionIntersectionDifference) {
  const Shape a{Circle{{0, 0}, 1}, "", ""};
  const Shape b{Rectangle{{0.5, -0.5}, {2.5, 0.5}}, "", ""};
  const Shape c{Ellipse{{-0.5, 0.5}, 1, 0.3}, "", ""};
  const Program pa = compile_geometry(a), pb = compile_geometry(b), pc = compile_geometry(c);
  const Program uni = compile_geometry(csg(CsgOp::kUnion, {a, b, c}));
  const Program inter = compile_geometry(csg(CsgOp::kIntersection, {a, b, c}));
  const Program diff = compile_geometry(csg(CsgOp::kDifference, {a, b, c}));
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int i = 0; i < 1000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    const double da = eval_sdf(pa.view(), p), db = eval_sdf(pb.view(), p),
                 dc = eval_sdf(pc.view(), p);
    EXPECT_EQ(eval_sdf(uni.view(), p), std::min({da, db, dc}));
    EXPECT_EQ(eval_sdf(inter.view(), p), std::max({da, db, dc}));
    EXPECT_EQ(eval_sdf(diff.view(), p), std::max({da, -db, -dc}));
  }
  // Known values: the union is exact outside, the difference has a hole where b is.
  const Program two = compile_geometry(csg(CsgOp::kUnion, {a, b}));
  EXPECT_DOUBLE_EQ(eval_sdf(two.view(), {3.5, 0}), 1.0);
  EXPECT_DOUBLE_EQ(eval_sdf(two.view(), {-3, 0}), 2.0);
  const Program minus = compile_geometry(csg(CsgOp::kDifference, {a, b}));
  EXPECT_DOUBLE_EQ(eval_sdf(minus.view(), {1.5, 0}), 0.5);  // outside a and inside b: max(0.5, 0.5)
  EXPECT_DOUBLE_EQ(eval_sdf(minus.view(), {1.2, 0.9}), std::hypot(1.2, 0.9) - 1);  // only a
  EXPECT_DOUBLE_EQ(eval_sdf(minus.view(), {0.75, 0}), 0.25);  // in both: -(-0.25)
  EXPECT_DOUBLE_EQ(eval_sdf(minus.view(), {-0.5, 0}), -0.5);
  // A single-operand union is the operand itself.
  EXPECT_EQ(eval_sdf(compile_geometry(csg(CsgOp::kUnion, {c})).view(), {0.1, 0.2}),
            eval_sdf(pc.view(), {0.1, 0.2}));
}

// ---- Transforms ---------------------------------------------------------------------------------

// d_T(p) = scale * d(T^-1 p) for a similarity T: what folding the transform must reproduce.
Vec2 inverse_apply(const Similarity& t, Vec2 p) {
  const Vec2 w = (1.0 / t.scale) * (p - t.offset);
  const double c = std::cos(t.angle), s = std::sin(t.angle);
  return {c * w.x + s * w.y, -s * w.x + c * w.y};
}

void expect_transform_folded(const Shape& shape, const Similarity& t, uint64_t seed) {
  const Program plain = compile_geometry(shape);
  const Program folded = compile_geometry(transformed(shape, t.scale, t.angle, t.offset));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 500; ++i) {
    const Vec2 p{u(rng), u(rng)};
    const double want = t.scale * eval_sdf(plain.view(), inverse_apply(t, p));
    // Folding rounds the parameters; the ellipse also solves for a root: allow a few ulps.
    ASSERT_NEAR(eval_sdf(folded.view(), p), want, 1e-12 * (1 + std::fabs(want)))
        << "at (" << p.x << ", " << p.y << ")";
  }
}

std::vector<Shape> every_primitive() {
  return {Shape{Circle{{0.3, -0.2}, 0.8}, "", ""},
          Shape{Rectangle{{-0.5, -0.3}, {1.2, 0.4}}, "", ""},
          Shape{Ellipse{{0.1, 0.2}, 1.5, 0.4}, "", ""},
          Shape{HalfPlane{{1, 2}, 0.5}, "", ""},
          Shape{Polygon{g3_polygon()}, "", ""},
          csg(CsgOp::kDifference,
              {Shape{Rectangle{{-1, -1}, {1, 1}}, "", ""}, Shape{Circle{{0, 0}, 0.5}, "", ""}})};
}

TEST(SdfEval, TranslateRotateScaleFoldIntoPrimitives) {
  const std::vector<Similarity> transforms = {
      {1.0, 0.0, {0.7, -1.3}},  // translate
      {1.0, 0.9, {0, 0}},       // rotate about the origin
      {2.5, 0.0, {0, 0}},       // scale
      {0.4, -2.2, {1.5, 0.5}},  // all three
  };
  uint64_t seed = 20;
  for (const Shape& shape : every_primitive())
    for (const Similarity& t : transforms) expect_transform_folded(shape, t, ++seed);
}

TEST(SdfEval, NestedTransformsCompose) {
  const Similarity inner{1.7, 0.4, {0.2, -0.6}}, outer{0.6, -1.1, {-1, 2}};
  const Similarity both = compose(outer, inner);
  // compose is "outer after inner".
  for (Vec2 p : {Vec2{0, 0}, Vec2{1, 2}, Vec2{-3, 0.5}}) {
    const Vec2 want = apply(outer, apply(inner, p)), got = apply(both, p);
    EXPECT_NEAR(got.x, want.x, 1e-14);
    EXPECT_NEAR(got.y, want.y, 1e-14);
  }
  uint64_t seed = 40;
  for (const Shape& shape : every_primitive()) {
    const Shape nested = transformed(transformed(shape, inner.scale, inner.angle, inner.offset),
                                     outer.scale, outer.angle, outer.offset);
    const Program folded = compile_geometry(nested);
    const Program plain = compile_geometry(shape);
    std::mt19937_64 rng(++seed);
    std::uniform_real_distribution<double> u(-4, 4);
    for (int i = 0; i < 300; ++i) {
      const Vec2 p{u(rng), u(rng)};
      const Vec2 q = inverse_apply(inner, inverse_apply(outer, p));
      const double want = outer.scale * inner.scale * eval_sdf(plain.view(), q);
      ASSERT_NEAR(eval_sdf(folded.view(), p), want, 1e-12 * (1 + std::fabs(want)));
    }
  }
  // A transform inside a CSG operand applies to that operand only.
  const Shape moved = transformed(Shape{Circle{{0, 0}, 1}, "", ""}, 1, 0, {10, 0});
  const Program u = compile_geometry(csg(CsgOp::kUnion, {Shape{Circle{{0, 0}, 1}, "", ""}, moved}));
  EXPECT_DOUBLE_EQ(eval_sdf(u.view(), {0, 0}), -1.0);
  EXPECT_DOUBLE_EQ(eval_sdf(u.view(), {10, 0}), -1.0);
  EXPECT_DOUBLE_EQ(eval_sdf(u.view(), {5, 0}), 4.0);
}

// ---- Owner --------------------------------------------------------------------------------------

int owner_at(const Program& program, Vec2 p) {
  int owner = -7;
  eval_sdf_range(program.view(), 0, static_cast<uint32_t>(program.code.size()), p, &owner);
  return owner;
}

TEST(SdfEval, OwnerIsThePrimitiveWhoseDistanceWins) {
  // Square minus a disk (G2): the hole owns points near the hole, the square the rest.
  const Program g2 =
      compile_geometry(csg(CsgOp::kDifference, {Shape{Rectangle{{-1, -1}, {1, 1}}, "outer", ""},
                                                Shape{Circle{{0, 0}, 0.5}, "hole", ""}}));
  ASSERT_EQ(g2.primitives.size(), 2u);
  EXPECT_EQ(g2.primitives[owner_at(g2, {0.55, 0})].name, "hole");
  EXPECT_EQ(g2.primitives[owner_at(g2, {0, -0.4})].name, "hole");  // inside the hole
  EXPECT_EQ(g2.primitives[owner_at(g2, {0.95, 0.1})].name, "outer");
  EXPECT_EQ(g2.primitives[owner_at(g2, {-1.5, 3})].name, "outer");  // outside the square
  for (Vec2 p : {Vec2{0.55, 0}, Vec2{0.95, 0.1}}) {  // owner's own distance is the result
    const int k = owner_at(g2, p);
    const double full = eval_sdf(g2.view(), p);  // the hole's distance enters negated
    const double own = sdf_primitive(g2.view(), g2.code[k], p);
    EXPECT_EQ(std::fabs(full), std::fabs(own));
  }

  // Union of three circles: the nearest circle owns points outside; ties go to the first.
  const Program u = compile_geometry(csg(
      CsgOp::kUnion, {Shape{Circle{{-2, 0}, 1}, "left", ""}, Shape{Circle{{0, 0}, 0.5}, "mid", ""},
                      Shape{Circle{{2, 0}, 1}, "right", ""}}));
  EXPECT_EQ(owner_at(u, {-3.5, 0}), 0);
  EXPECT_EQ(owner_at(u, {0, 0.7}), 1);
  EXPECT_EQ(owner_at(u, {2.1, -1.2}), 2);
  EXPECT_EQ(owner_at(u, {0, -3}), 1);  // 2.5 to mid, about 3.6 - 1 to the others

  // Intersection: the farthest (max) operand owns.
  const Program i =
      compile_geometry(csg(CsgOp::kIntersection, {Shape{Circle{{0, 0}, 1}, "disk", ""},
                                                  Shape{HalfPlane{{0, 1}, 0.25}, "cut", ""}}));
  EXPECT_EQ(owner_at(i, {0, 0.2}), 1);
  EXPECT_EQ(owner_at(i, {0.9, -0.3}), 0);
  // Owner indices follow the instruction's primitive index even under transforms.
  const Program t = compile_geometry(
      csg(CsgOp::kUnion, {transformed(Shape{Circle{{0, 0}, 1}, "a", ""}, 1, 0, {5, 0}),
                          Shape{Circle{{0, 0}, 1}, "b", ""}}));
  EXPECT_EQ(t.primitives[owner_at(t, {6.5, 0})].name, "a");
  EXPECT_EQ(t.primitives[owner_at(t, {-1.5, 0})].name, "b");
}

TEST(SdfEval, OwnerOfAnInstructionRange) {
  // Size fields evaluate sub-ranges of one program (one per distance term); the owner and the
  // value come from that range alone, with primitive indices of the whole program.
  SizeFieldSpec spec;
  for (double x : {0.0, 5.0}) {
    DistanceSize term;
    term.shape = Shape{Circle{{x, 0}, 1}, "", ""};
    spec.terms.push_back(term);
  }
  const SizeProgram size = compile_size_field(spec);
  ASSERT_EQ(size.terms.size(), 2u);
  const SizeTermCode second = size.terms[1];
  int owner = -1;
  const double d = eval_sdf_range(size.shapes.view(), second.begin, second.end, {0, 0}, &owner);
  EXPECT_DOUBLE_EQ(d, 4.0);
  EXPECT_EQ(owner, 1);
  EXPECT_DOUBLE_EQ(
      eval_sdf_range(size.shapes.view(), size.terms[0].begin, size.terms[0].end, {0, 0}, &owner),
      -1.0);
  EXPECT_EQ(owner, 0);
}

}  // namespace
}  // namespace meshd
