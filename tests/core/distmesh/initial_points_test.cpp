// Steps 1-2 of DistMesh: the equilateral grid, the fd < geps filter and the size-based
// rejection, both through initial_points.cuh and through CpuEngine::initialize.
#include "core/distmesh/initial_points.cuh"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

constexpr double kHalfSqrt3 = 0.8660254037844386;

std::vector<Vec2> initial_points(const CompiledProblem& problem, unsigned threads = 0) {
  ThreadPool pool(threads);
  CpuEngine engine(pool);
  engine.initialize(problem);
  std::vector<Vec2> points;
  engine.read_points(points);
  return points;
}

// ---- The grid -----------------------------------------------------------------------------------

TEST(InitialGrid, NearlyEquilateralRowsOddRowsShiftedSpanningTheBox) {
  const double h0 = 0.125;
  const Box box{{-1, 2}, {0.5, 3}};
  const InitialGrid g = make_initial_grid(box, h0);
  EXPECT_EQ(g.nx, 13);  // 1.5 / 0.125 = 12 columns
  EXPECT_EQ(g.ny, 10);  // 1 / (0.125 sqrt(3)/2) = 9.24 -> 9 rows of spacing
  // Spacings stretch by less than half a spacing over the box, so that the grid spans it.
  EXPECT_DOUBLE_EQ(g.dx, 0.125);
  EXPECT_DOUBLE_EQ(g.dy, 1.0 / 9);
  EXPECT_LT(std::fabs(g.dy - h0 * kHalfSqrt3), 0.5 * h0 * kHalfSqrt3 / 9);
  for (int64_t j = 0; j < g.ny; ++j) {
    for (int64_t i = 0; i < g.nx; ++i) {
      const Vec2 p = initial_grid_point(g, j * g.nx + i);
      EXPECT_NEAR(p.x, -1 + g.dx * i + (j % 2 == 1 ? g.dx / 2 : 0.0), 1e-15);
      EXPECT_NEAR(p.y, 2 + g.dy * j, 1e-15);
      if (j > 0) {
        // Each point is about h0 from its neighbours in the row below.
        const Vec2 below = initial_grid_point(g, (j - 1) * g.nx + i);
        EXPECT_NEAR(norm(p - below), h0, 0.03 * h0);
      }
    }
  }
  // Even rows start on the box's left side and end on its right; rows reach bottom and top.
  EXPECT_EQ(initial_grid_point(g, 0).x, -1.0);
  EXPECT_EQ(initial_grid_point(g, 0).y, 2.0);
  EXPECT_DOUBLE_EQ(initial_grid_point(g, g.nx - 1).x, 0.5);
  EXPECT_DOUBLE_EQ(initial_grid_point(g, g.nx * (g.ny - 1)).y, 3.0);
}

TEST(InitialPoints, KeepsExactlyTheGridPointsWithFdBelowGeps) {
  // G1 without fixed points: every grid point with fd < geps, in grid order, bitwise.
  const CompiledProblem c = compile_problem(testing::benchmark_problem("G1", 0.1));
  ASSERT_TRUE(c.fixed_points.empty());
  const InitialGrid g = make_initial_grid(c.bbox, c.h0);
  const double geps = c.params.geps * c.h0;
  std::vector<Vec2> want;
  for (int64_t k = 0; k < g.nx * g.ny; ++k) {
    const Vec2 p = initial_grid_point(g, k);
    if (eval_sdf(c.geometry.view(), p) < geps) want.push_back(p);
  }
  const std::vector<Vec2> got = initial_points(c);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) EXPECT_TRUE(got[i] == want[i]) << i;
  // About the disk's area in equilateral cells of area h0^2 sqrt(3)/2.
  EXPECT_NEAR(static_cast<double>(got.size()), M_PI / (0.01 * kHalfSqrt3), 15);
  // Every kept point is inside or within geps of the boundary.
  for (Vec2 p : got) EXPECT_LT(eval_sdf(c.geometry.view(), p), geps);
}

TEST(InitialPoints, FixedPointsComeFirstAndPushAwayGridPoints) {
  // G2: the 4 square corners are fixed; the grid starts at (-1, -1), on top of one of them.
  const CompiledProblem c = compile_problem(testing::benchmark_problem("G2", 0.1));
  ASSERT_EQ(c.fixed_points.size(), 4u);
  const std::vector<Vec2> got = initial_points(c);
  for (size_t f = 0; f < 4; ++f) EXPECT_TRUE(got[f] == c.fixed_points[f]) << f;
  for (size_t i = 4; i < got.size(); ++i) {
    for (Vec2 f : c.fixed_points) EXPECT_GE(norm(got[i] - f), 0.5 * c.h0) << i;
    EXPECT_LT(eval_sdf(c.geometry.view(), got[i]), c.params.geps * c.h0);
    // None inside the hole.
    EXPECT_GE(norm(got[i]), 0.5 - c.params.geps * c.h0);
  }
  // Everything else of the filtered grid is kept: the count matches.
  const InitialGrid g = make_initial_grid(c.bbox, c.h0);
  int64_t inside = 0, near_fixed = 0;
  for (int64_t k = 0; k < g.nx * g.ny; ++k) {
    const Vec2 p = initial_grid_point(g, k);
    if (eval_sdf(c.geometry.view(), p) >= c.params.geps * c.h0) continue;
    ++inside;
    for (Vec2 f : c.fixed_points)
      if (norm(p - f) < 0.5 * c.h0) {
        ++near_fixed;
        break;
      }
  }
  EXPECT_GE(near_fixed, 1);  // the corner (-1, -1) at least
  EXPECT_EQ(static_cast<int64_t>(got.size()), 4 + inside - near_fixed);
}

// ---- Size-based rejection -----------------------------------------------------------------------

TEST(SizeRejection, ThresholdsArePureAndEvenlySpread) {
  const InitialGrid g = make_initial_grid(Box{{0, 0}, {100, 100}}, 0.05);  // 2,001 per row
  for (uint64_t seed : {0ull, 1ull, 12345ull}) {
    for (int64_t k : {0ll, 1ll, 77ll, 1ll << 40}) {
      EXPECT_EQ(dither_threshold(seed, g, k), dither_threshold(seed, g, k));
      EXPECT_EQ(keep_by_size(seed, g, k, 1.7, 1.0), keep_by_size(seed, g, k, 1.7, 1.0));
    }
  }
  // In [0, 1), and even in every 8 x 8 block of grid points: 16 +- 2 of 64 under a quarter (an
  // independent draw per point gives 16 +- 3.5 as one standard deviation). Seeds differ.
  int same = 0;
  for (int64_t row = 0; row < 400; row += 8) {
    for (int64_t column = 0; column < 400; column += 8) {
      int below_quarter = 0;
      for (int64_t j = row; j < row + 8; ++j) {
        for (int64_t i = column; i < column + 8; ++i) {
          const double t = dither_threshold(7, g, j * g.nx + i);
          ASSERT_GE(t, 0.0);
          ASSERT_LT(t, 1.0);
          below_quarter += t < 0.25;
          same += dither_threshold(8, g, j * g.nx + i) == t;
        }
      }
      EXPECT_NEAR(below_quarter, 16, 2) << "block at column " << column << ", row " << row;
    }
  }
  EXPECT_LT(same, 5);
  // Where the size is the smallest, every point is kept.
  for (int k = 0; k < 1000; ++k) EXPECT_TRUE(keep_by_size(3, g, k, 0.4, 0.4));
  // keep_by_size keeps exactly when the threshold is under (h_min / h)^2.
  for (int k = 0; k < 1000; ++k)
    EXPECT_EQ(keep_by_size(3, g, k, 2.0, 1.0), dither_threshold(3, g, k) < 0.25);
}

// The grid points G5 keeps for `seed`, computed from the formulas: fd < geps, then the dither.
std::vector<Vec2> expected_g5_points(const CompiledProblem& c, uint64_t seed, double* mean_kept) {
  const InitialGrid g = make_initial_grid(c.bbox, c.h0);
  const double geps = c.params.geps * c.h0;
  std::vector<int64_t> inside;
  std::vector<double> size;
  double h_min = INFINITY;
  for (int64_t k = 0; k < g.nx * g.ny; ++k) {
    const Vec2 p = initial_grid_point(g, k);
    if (eval_sdf(c.geometry.view(), p) >= geps) continue;
    inside.push_back(k);
    size.push_back(eval_size(c.size.view(), p));
    h_min = std::min(h_min, size.back());
  }
  std::vector<Vec2> kept(c.fixed_points.begin(), c.fixed_points.end());
  double mean = 0;
  for (size_t i = 0; i < inside.size(); ++i) {
    const double ratio = h_min / size[i];
    mean += ratio * ratio;
    if (!(dither_threshold(seed, g, inside[i]) < ratio * ratio)) continue;
    const Vec2 p = initial_grid_point(g, inside[i]);
    bool near_fixed = false;
    for (Vec2 f : c.fixed_points) near_fixed = near_fixed || norm(p - f) < 0.5 * c.h0 * size[i];
    if (!near_fixed) kept.push_back(p);
  }
  if (mean_kept != nullptr) *mean_kept = mean;
  return kept;
}

TEST(SizeRejection, GradedCaseKeepsTheExpectedPointsAndFraction) {
  Problem p = testing::benchmark_problem("G5", 0.02);
  p.seed = 42;
  const CompiledProblem c = compile_problem(p);
  double mean_kept = 0;
  const std::vector<Vec2> want = expected_g5_points(c, p.seed, &mean_kept);
  const std::vector<Vec2> got = initial_points(c);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) ASSERT_TRUE(got[i] == want[i]) << i;

  // The kept fraction is sum (h_min / h)^2 over the inside points, within 1% (the dither's
  // error; an independent draw per point is off by sqrt(n)). For h = min(4r - 1, 2) that is well
  // under a half: far fewer points than the uniform grid.
  const double kept = static_cast<double>(got.size() - c.fixed_points.size());
  EXPECT_NEAR(kept, mean_kept, 0.01 * mean_kept);
  EXPECT_GT(mean_kept, 1000);

  // A point at size h survives with probability (h_min / h)^2: near the hole (h ~ 1) almost all
  // are kept; where h = 2, about a quarter.
  int64_t far_total = 0, far_kept = 0;
  const InitialGrid g = make_initial_grid(c.bbox, c.h0);
  for (int64_t k = 0; k < g.nx * g.ny; ++k) {
    const Vec2 q = initial_grid_point(g, k);
    if (eval_sdf(c.geometry.view(), q) >= 0 || norm(q) < 0.8) continue;
    ++far_total;
  }
  for (Vec2 q : got) far_kept += norm(q) >= 0.8 && eval_sdf(c.geometry.view(), q) < 0;
  const double h_min = 4 * 0.5 - 1;  // the hole's boundary: grid points come within geps of it
  const double p_far = (h_min / 2) * (h_min / 2);
  EXPECT_NEAR(static_cast<double>(far_kept) / far_total, p_far * 1.0, 0.03);
}

TEST(SizeRejection, DeterministicInTheSeedAcrossThreadCounts) {
  Problem p = testing::benchmark_problem("G5", 0.03);
  p.seed = 9;
  const CompiledProblem c = compile_problem(p);
  const std::vector<Vec2> one = initial_points(c, 1), two = initial_points(c, 2),
                          again = initial_points(c, 3);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_EQ(one.size(), again.size());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_TRUE(one[i] == two[i]) << i;
    EXPECT_TRUE(one[i] == again[i]) << i;
  }
  // Another seed keeps another subset.
  p.seed = 10;
  const std::vector<Vec2> other = initial_points(compile_problem(p));
  size_t differ = one.size() != other.size();
  for (size_t i = 0; i < std::min(one.size(), other.size()); ++i) differ += !(one[i] == other[i]);
  EXPECT_GT(differ, 10u);
  // A uniform size keeps every inside point whatever the seed.
  Problem u = testing::benchmark_problem("G2", 0.05);
  u.seed = 1;
  const size_t n1 = initial_points(compile_problem(u)).size();
  u.seed = 2;
  EXPECT_EQ(initial_points(compile_problem(u)).size(), n1);
}

}  // namespace
}  // namespace meshd
