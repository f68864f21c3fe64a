// Distance grids (grid_sdf.cuh) against the analytic shapes they sample: signs and values within
// the interpolation error, the box outside the grid, transforms folded like other primitives,
// CSG with other primitives, a size field's distance, bounds, corners and projection onto the
// boundary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/geometry/boundary_crossings.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry/projection.cuh"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

using testing::circle;
using testing::csg;
using testing::disk_grid;
using testing::distance_grid;
using testing::rectangle;
using testing::transformed;

constexpr uint32_t kN = 61;                 // samples per axis over [-1.5, 1.5]
constexpr double kH = 3.0 / (kN - 1);       // 0.05
constexpr double kInterpolation = kH * kH;  // bilinear error of |p| - 1 away from its apex

double eval(const Program& p, Vec2 q) { return eval_sdf(p.view(), q); }

std::vector<Vec2> random_points(Box b, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(b.min.x, b.max.x), y(b.min.y, b.max.y);
  std::vector<Vec2> out;
  for (int k = 0; k < n; ++k) out.push_back({x(rng), y(rng)});
  return out;
}

TEST(DistanceGrid, SampledDiskMatchesTheDiskWithinInterpolationError) {
  const Program grid = compile_geometry(disk_grid(kN));
  int inside = 0, outside = 0;
  for (Vec2 p : random_points({{-1.5, -1.5}, {1.5, 1.5}}, 20000, 1)) {
    const double exact = norm(p) - 1.0, d = eval(grid, p);
    // The cone's apex (|p| = 0) is no smooth distance: interpolation errs by up to h there;
    // elsewhere by at most h^2 / (4 |p|).
    if (norm(p) > 0.5) {
      EXPECT_NEAR(d, exact, kInterpolation) << p.x << " " << p.y;
    }
    if (exact < -kInterpolation) {
      EXPECT_LT(d, 0.0);
      ++inside;
    }
    if (exact > kInterpolation) {
      EXPECT_GT(d, 0.0);
      ++outside;
    }
  }
  EXPECT_GT(inside, 5000);
  EXPECT_GT(outside, 3000);
  // At the samples themselves, the sample (to single precision).
  EXPECT_NEAR(eval(grid, {1.0, 0.0}), 0.0, 1e-7);
  EXPECT_NEAR(eval(grid, {0.0, 0.0}), -1.0, 1e-7);
}

TEST(DistanceGrid, OutsideItsBoxTheBoxDistanceBoundsItFromBelow) {
  const Program grid = compile_geometry(disk_grid(kN));
  const Box box{{-1.5, -1.5}, {1.5, 1.5}};
  for (Vec2 p : random_points({{-6, -6}, {6, 6}}, 5000, 2)) {
    const double d = eval(grid, p), to_box = std::sqrt(box_distance2(box, p));
    if (to_box == 0.0) continue;
    EXPECT_GE(d, to_box - 1e-12);
    // Never closer to the disk than it is: clamping onto the box does not move p away.
    EXPECT_LE(d, norm(p) - 1.0 + kInterpolation);
  }
  // A grid negative everywhere is its box, exactly.
  const Program square =
      compile_geometry(distance_grid([](Vec2) { return -1.0; }, {0, 0}, 0.5, 5, 3));
  EXPECT_NEAR(eval(square, {3, 2}), std::hypot(1.0, 1.0), 1e-12);
  EXPECT_NEAR(eval(square, {1, 0.5}), -0.5, 1e-12);
  EXPECT_NEAR(eval(square, {1, -0.25}), 0.25, 1e-12);
}

TEST(DistanceGrid, TransformsMoveItLikeTheShapeItSamples) {
  const double scale = 2.5, angle = 0.7;
  const Vec2 offset{3.0, -1.0};
  // An off-centre disk, so that rotation and translation both show.
  auto f = [](Vec2 p) { return norm(p - Vec2{0.2, -0.1}) - 0.9; };
  const Program grid = compile_geometry(
      transformed(distance_grid(f, {-1.5, -1.5}, kH, kN, kN), scale, angle, offset));
  const Program disk =
      compile_geometry(transformed(circle({0.2, -0.1}, 0.9), scale, angle, offset));
  const Box near = program_bounds(disk);
  for (Vec2 p : random_points(near, 5000, 3)) {
    if (eval(disk, p) < scale * (0.5 - 0.9)) continue;  // near the apex (first test)
    EXPECT_NEAR(eval(grid, p), eval(disk, p), scale * kInterpolation) << p.x << " " << p.y;
  }
  // Bounds: the grid's box [-1.5, 1.5]^2, rotated, scaled and moved.
  const Box b = program_bounds(grid);
  const double half = scale * 1.5 * (std::fabs(std::cos(angle)) + std::fabs(std::sin(angle)));
  EXPECT_NEAR(b.min.x, offset.x - half, 1e-12);
  EXPECT_NEAR(b.max.y, offset.y + half, 1e-12);
  EXPECT_DOUBLE_EQ(distance_bound_box(grid, 0, 1).min.x, b.min.x);
}

TEST(DistanceGrid, CombinesWithOtherPrimitives) {
  // (sampled disk minus an exact disk) union a rectangle, against the all-analytic tree.
  auto tree = [](Shape outer) {
    return csg(CsgOp::kUnion, {csg(CsgOp::kDifference, {std::move(outer), circle({0.3, 0}, 0.4)}),
                               rectangle({0.8, -0.2}, {2.0, 0.2})});
  };
  const Program grid = compile_geometry(tree(disk_grid(kN)));
  const Program exact = compile_geometry(tree(circle({0, 0}, 1)));
  for (Vec2 p : random_points({{-2, -2}, {2.5, 2}}, 10000, 4)) {
    const double e = eval(exact, p), d = eval(grid, p);
    // Within the grid's box (beyond it the grid gives the box's distance, a lower bound).
    if (norm(p) > 0.5 && std::fabs(p.x) <= 1.5 && std::fabs(p.y) <= 1.5) {
      EXPECT_NEAR(d, e, kInterpolation);
    }
    if (std::fabs(e) > kInterpolation) {
      EXPECT_EQ(d < 0, e < 0) << p.x << " " << p.y;
    }
  }
  // An indexed union of many grids (its tree's boxes come from distance_bound_box) agrees with
  // the plain fold of the same grids.
  std::vector<Shape> many;
  for (int k = 0; k < 12; ++k)
    many.push_back(transformed(disk_grid(21), 0.3, 0.1 * k, {1.0 * (k % 4), 1.0 * (k / 4)}));
  const Program indexed = compile_geometry(csg(CsgOp::kUnion, many));
  ASSERT_EQ(indexed.code.front().op, Op::kUnionIndexed);
  ASSERT_NE(indexed.code.front().bvh, kNoBvh);
  for (Vec2 p : random_points({{-1, -1}, {4, 3}}, 3000, 5)) {
    const double fold = eval_program<0>(indexed.view(), 0, indexed.view().size, p, nullptr);
    EXPECT_EQ(eval(indexed, p), fold);
  }
}

TEST(DistanceGrid, GradesASizeFieldLikeTheShapeItSamples) {
  auto field = [](Shape shape) {
    SizeFieldSpec spec;
    spec.terms.push_back(DistanceSize{std::move(shape), 1.0, 2.0, 3.0});
    return compile_size_field(spec);
  };
  const SizeProgram grid = field(disk_grid(kN)), exact = field(circle({0, 0}, 1));
  ASSERT_FALSE(grid.shapes.samples.empty());
  for (Vec2 p : random_points({{-1.5, -1.5}, {1.5, 1.5}}, 5000, 7)) {
    if (norm(p) < 0.5) continue;
    EXPECT_NEAR(eval_size(grid.view(), p), eval_size(exact.view(), p), 2.0 * kInterpolation);
  }
}

TEST(DistanceGrid, NamedLikeOtherPrimitives) {
  const Program p =
      compile_geometry(csg(CsgOp::kUnion, {disk_grid(11), disk_grid(11, "organ"), disk_grid(11)}));
  ASSERT_EQ(p.primitives.size(), 3u);
  EXPECT_EQ(p.primitives[0].name, "distance_grid1");
  EXPECT_EQ(p.primitives[1].name, "organ");
  EXPECT_EQ(p.primitives[2].name, "distance_grid2");
}

TEST(DistanceGrid, CornersOnlyWhereItsBoxCornersAreOnTheBoundary) {
  // A smooth zero level inside the box: no corner, and no curve to cross another primitive's.
  const Program disk = compile_geometry(disk_grid(kN));
  EXPECT_TRUE(boundary_corners(disk, program_bounds(disk)).empty());
  const Program crossed =
      compile_geometry(csg(CsgOp::kUnion, {disk_grid(kN), circle({1, 0}, 0.5)}));
  EXPECT_TRUE(boundary_crossings(crossed, program_bounds(crossed)).empty());
  // Negative everywhere: the domain is the (rotated) box, whose corners are corners.
  const Program square =
      compile_geometry(transformed(distance_grid([](Vec2) { return -1.0; }, {0, 0}, 0.5, 5, 3), 2.0,
                                   std::numbers::pi / 6, {1, 1}));
  const std::vector<Vec2> corners = boundary_corners(square, program_bounds(square));
  ASSERT_EQ(corners.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    const Vec2 want{square.primitives[0].corners[2 * k], square.primitives[0].corners[2 * k + 1]};
    EXPECT_TRUE(std::any_of(corners.begin(), corners.end(),
                            [&](Vec2 c) { return norm(c - want) < 1e-12; }));
  }
}

TEST(DistanceGrid, CornersWhereItsZeroLevelMeetsItsBox) {
  // The unit disk cut by the grid's bottom side at y = 0 (the samples start off the sample grid
  // of the first test, so that the crossings fall between samples): a half disk whose two
  // corners are where the circle meets the side; moved, turned and scaled with the grid.
  const Shape half = distance_grid([](Vec2 p) { return norm(p) - 1.0; }, {-1.52, 0.0}, kH, 62, 31);
  for (double scale : {1.0, 3.0}) {
    const Similarity t{scale, 0.4, {2, -1}};
    const Program p = compile_geometry(transformed(half, t.scale, t.angle, t.offset));
    const std::vector<Vec2> corners = boundary_corners(p, program_bounds(p));
    ASSERT_EQ(corners.size(), 2u) << scale;
    for (Vec2 want : {apply(t, {-1, 0}), apply(t, {1, 0})}) {
      EXPECT_TRUE(std::any_of(corners.begin(), corners.end(),
                              [&](Vec2 c) { return norm(c - want) < 1e-6 * scale; }))
          << want.x << " " << want.y;
    }
  }
  // A level that runs along a side (a tangent) is no corner: the disk touching the top side.
  const Program touching = compile_geometry(
      distance_grid([](Vec2 p) { return norm(p) - 1.0; }, {-1.5, -1.5}, 0.05, 61, 51));
  EXPECT_TRUE(boundary_corners(touching, program_bounds(touching)).empty());
}

TEST(DistanceGrid, ProjectionLandsOnItsZeroLevel) {
  // The numerical gradient of projection.cuh on a bilinear field: forward differences along an
  // axis are exact within a cell, so Newton's steps converge to the interpolant's zero level.
  const Program grid = compile_geometry(disk_grid(kN));
  const double h0 = 0.05, deps = 1.4901161193847656e-8 * h0;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), radius(0.9, 1.1);
  double worst = 0, worst_circle = 0;
  for (int k = 0; k < 2000; ++k) {
    const double a = angle(rng), r = radius(rng);
    const Vec2 q = project_to_boundary(grid.view(), {r * std::cos(a), r * std::sin(a)}, deps);
    worst = std::max(worst, std::fabs(eval(grid, q)));
    worst_circle = std::max(worst_circle, std::fabs(norm(q) - 1.0));
  }
  EXPECT_LE(worst, 1e-6 * h0);
  EXPECT_LE(worst_circle, kInterpolation);
}

}  // namespace
}  // namespace meshd
