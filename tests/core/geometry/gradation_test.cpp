// Gradient limiting (gradation.h): it never raises a value, leaves a compliant field alone,
// bounds the growth between neighbours by g, and turns a point-like small size into a cone of
// slope g; through compile_problem, the edge length h0 * h grows by at most the gradation.
#include "core/geometry/gradation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <random>
#include <utility>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/compile.h"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

GridSize constant_grid(uint32_t nx, uint32_t ny, Vec2 spacing, float value) {
  GridSize g;
  g.origin = {0, 0};
  g.spacing = spacing;
  g.nx = nx;
  g.ny = ny;
  g.values.assign(size_t(nx) * ny, value);
  return g;
}

float& at(GridSize& g, uint32_t i, uint32_t j) { return g.values[size_t(j) * g.nx + i]; }

// The largest |h(p) - h(q)| / |p - q| over adjacent samples (rows, columns and diagonals).
double steepest_step(const GridSize& g) {
  double worst = 0;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i)
      for (auto [di, dj] : {std::pair{1, 0}, {0, 1}, {1, 1}, {1, -1}}) {
        const int a = int(i) + di, b = int(j) + dj;
        if (a >= int(g.nx) || b < 0 || b >= int(g.ny)) continue;
        const double rise =
            std::fabs(g.values[size_t(b) * g.nx + a] - g.values[size_t(j) * g.nx + i]);
        worst = std::max(worst, rise / std::hypot(di * g.spacing.x, dj * g.spacing.y));
      }
  return worst;
}

TEST(Gradation, APointBecomesAConeOfSlopeG) {
  GridSize g = constant_grid(101, 81, {0.01, 0.01}, 1.0f);
  at(g, 50, 40) = 0.1f;  // at (0.5, 0.4)
  const GridSize input = g;
  const double slope = 2.0;
  limit_gradient(g, slope);
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) {
      const double r = std::hypot(i * 0.01 - 0.5, j * 0.01 - 0.4);
      const double cone = 0.1 + slope * r, h = at(g, i, j);
      ASSERT_LE(h, input.values[size_t(j) * g.nx + i]);  // never raised
      // On the cone, up to the path's 3% detour and single precision; capped by the input.
      ASSERT_GE(h, std::min(1.0, cone) - 1e-6) << i << " " << j;
      ASSERT_LE(h, std::min(1.0, 0.1 + 1.03 * slope * r) + 1e-6) << i << " " << j;
    }
  // Exactly the cone along the grid's rows and columns through the point.
  EXPECT_NEAR(at(g, 60, 40), 0.1 + slope * 0.1, 1e-6);
  EXPECT_NEAR(at(g, 50, 60), 0.1 + slope * 0.2, 1e-6);
  EXPECT_NEAR(at(g, 60, 50), 0.1 + slope * std::hypot(0.1, 0.1), 1e-6);  // and its diagonals
  EXPECT_LE(steepest_step(g), slope * (1 + 1e-5));
  EXPECT_GT(steepest_step(input), 10 * slope);
}

TEST(Gradation, LeavesACompliantFieldAloneAndIsIdempotent) {
  GridSize ramp = constant_grid(30, 20, {0.1, 0.2}, 0);
  for (uint32_t j = 0; j < ramp.ny; ++j)
    for (uint32_t i = 0; i < ramp.nx; ++i)
      at(ramp, i, j) = 1.0f + 0.5f * i * 0.1f + 0.25f * j * 0.2f;
  GridSize limited = ramp;
  limit_gradient(limited, 1.0);  // |grad| = hypot(0.5, 0.25) < 1
  EXPECT_EQ(limited.values, ramp.values);

  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(0.1f, 3.0f);
  GridSize noise = constant_grid(40, 50, {0.05, 0.03}, 0);
  for (float& v : noise.values) v = value(rng);
  GridSize once = noise;
  limit_gradient(once, 0.7);
  for (size_t k = 0; k < noise.values.size(); ++k) ASSERT_LE(once.values[k], noise.values[k]);
  EXPECT_LE(steepest_step(once), 0.7 * (1 + 1e-5));
  GridSize twice = once;
  limit_gradient(twice, 0.7);  // the same, up to the rounding of each sample to single precision
  for (size_t k = 0; k < once.values.size(); ++k)
    ASSERT_NEAR(twice.values[k], once.values[k], 1e-6 * once.values[k]);
}

// The settling of gradation.h in Dijkstra's order, from the smallest samples outwards, each
// value settled once: the reference that the sweeps must match bit for bit.
std::vector<float> settled_in_dijkstras_order(const GridSize& grid, double g) {
  constexpr std::pair<int, int> kSteps[] = {{1, 0},  {-1, 0},  {0, 1},  {0, -1}, {1, 1},  {1, -1},
                                            {-1, 1}, {-1, -1}, {1, 2},  {1, -2}, {-1, 2}, {-1, -2},
                                            {2, 1},  {2, -1},  {-2, 1}, {-2, -1}};
  const int nx = int(grid.nx), ny = int(grid.ny);
  std::vector<double> h(grid.values.begin(), grid.values.end());
  using Entry = std::pair<double, int64_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int64_t k = 0; k < int64_t(h.size()); ++k) queue.push({h[k], k});
  while (!queue.empty()) {
    const auto [value, k] = queue.top();
    queue.pop();
    if (value > h[k]) continue;
    for (auto [di, dj] : kSteps) {
      const int a = int(k % nx) + di, b = int(k / nx) + dj;
      if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
      const double bound = value + g * std::hypot(di * grid.spacing.x, dj * grid.spacing.y);
      const int64_t n = int64_t(b) * nx + a;
      if (bound < h[n]) queue.push({h[n] = bound, n});
    }
  }
  std::vector<float> out(grid.values);
  for (size_t k = 0; k < h.size(); ++k) out[k] = std::min(out[k], float(h[k]));
  return out;
}

TEST(Gradation, TheSweepsEndWhereDijkstrasOrderEnds) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 12; ++trial) {
    const uint32_t nx = 5 + rng() % 90, ny = 3 + rng() % 70;
    const Vec2 spacing{0.01 + 0.1 * (rng() % 100) / 100.0, 0.01 + 0.1 * (rng() % 100) / 100.0};
    GridSize grid = constant_grid(nx, ny, spacing, 0);
    std::uniform_real_distribution<float> value(1.0f, 20.0f);
    if (trial % 3 == 0) {
      for (float& v : grid.values) v = value(rng);  // noise everywhere
    } else {
      // A plateau with a few small sizes: the cones of a shoreline field.
      for (float& v : grid.values) v = 20.0f;
      for (int k = 0; k < 1 + trial; ++k) grid.values[rng() % grid.values.size()] = value(rng);
    }
    const double g = 0.2 + 5.0 * (rng() % 100) / 100.0;
    const std::vector<float> want = settled_in_dijkstras_order(grid, g);
    limit_gradient(grid, g);
    ASSERT_EQ(grid.values, want) << "trial " << trial << ": " << nx << " x " << ny;
  }
}

TEST(Gradation, SamplesTheFieldOverTheBoxWithinTheBudget) {
  SizeFieldSpec spec;
  spec.terms.push_back(UniformSize{2.0});
  const SizeProgram size = compile_size_field(spec);
  const GridSize fine = limited_size_grid(size, {{0, 0}, {3, 2}}, 0.1, 1.0);
  EXPECT_EQ(fine.nx, 31u);
  EXPECT_EQ(fine.ny, 21u);
  EXPECT_DOUBLE_EQ(fine.origin.x, 0);
  EXPECT_DOUBLE_EQ(fine.spacing.x, 0.1);
  EXPECT_DOUBLE_EQ(fine.scale, 2.0);  // samples relative to the field's lower bound
  EXPECT_TRUE(std::all_of(fine.values.begin(), fine.values.end(), [](float v) { return v == 1; }));
  // A cell far too small for the box: coarser, within the budget.
  const GridSize capped = limited_size_grid(size, {{0, 0}, {1e4, 1}}, 1e-6, 1.0);
  EXPECT_LE(double(capped.nx) * capped.ny, kMaxGradationSamples);
  EXPECT_GE(capped.ny, 2u);
  EXPECT_NEAR(capped.origin.x + (capped.nx - 1) * capped.spacing.x, 1e4, 1e-6);
}

// The samples spread over threads land where the caller's thread alone puts them.
TEST(Gradation, SamplesOverThreadsAsOnOne) {
  SizeFieldSpec spec;  // 0.5 at a circle, growing 4 per length unit up to 3
  spec.terms.push_back(DistanceSize{Shape{Circle{{1, 0.5}, 0.3}, "", ""}, 0.5, 4, 3});
  const SizeProgram size = compile_size_field(spec);
  const Box box{{0, 0}, {3, 2}};
  const GridSize alone = limited_size_grid(size, box, 0.005, 0.8);  // 601 x 401: 15 pieces
  ThreadPool pool(4);
  const GridSize shared = limited_size_grid(size, box, 0.005, 0.8, &pool);
  EXPECT_EQ(shared.values, alone.values);
}

// Through compile_problem: a distance term that is small only at a point (0.25 there, 1 a grid
// cell away), in a field of 1, with gradation g at h0 = 0.02: the edge length h0 * h rises from
// the point at slope g.
TEST(Gradation, CompiledFieldGrowsTheEdgeLengthAtTheGradation) {
  Problem p;
  p.geometry = Shape{Rectangle{{0, 0}, {2, 1}}, "", ""};
  DistanceSize point;
  point.shape = Shape{Circle{{1, 0.5}, 1e-9}, "", ""};
  point.h_min = 0.25;
  point.slope = 1e3;
  point.h_max = 1.0;
  p.size.terms.push_back(point);
  p.size.gradation = 0.3;
  p.h0 = 0.02;
  const CompiledProblem c = compile_problem(p);
  ASSERT_EQ(c.size.terms.size(), 1u);
  EXPECT_NE(c.size.terms[0].grid, kNoGrid);
  // Edge lengths: c.h0 * eval_size is h0 * h whatever the rescaling.
  auto edge = [&](Vec2 q) { return c.h0 * eval_size(c.size.view(), q); };
  EXPECT_NEAR(edge({1, 0.5}), 0.02 * 0.25, 1e-6);  // a sample of the grid
  for (double r : {0.01, 0.02, 0.04}) {
    const double expected = 0.02 * 0.25 + 0.3 * r;
    EXPECT_NEAR(edge({1 + r, 0.5}), expected, 0.05 * expected) << r;
    EXPECT_LE(edge({1, 0.5 + r}), 1.03 * expected + 1e-4) << r;
  }
  EXPECT_NEAR(edge({0.1, 0.1}), 0.02, 1e-6);  // far away: the field's own 1
  // sampled_size_field gives the same grid, ready for the service to keep.
  const SizeFieldSpec graded = sampled_size_field(p);
  ASSERT_EQ(graded.terms.size(), 1u);
  EXPECT_EQ(graded.gradation, 0.0);
  const GridSize& g = std::get<GridSize>(graded.terms[0]);
  EXPECT_LE(double(g.nx) * g.ny, kMaxGradationSamples);
  EXPECT_NEAR(g.spacing.x, 0.5 * 0.02 * 0.25, 1e-4);  // half the finest edge
}

}  // namespace
}  // namespace meshd
