// Grid terms of the size field: the one evaluator reads them by bilinear interpolation, takes
// the minimum with the other terms, extends the border outwards, and compile_problem folds the
// field's lower bound into h0 for them as for the other terms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/compile.h"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// h = 1 + x / 2 on [0, 4] x [0, 1]: linear, so bilinear interpolation returns it exactly.
GridSize ramp() {
  GridSize g;
  g.origin = {0, 0};
  g.spacing = {0.5, 0.5};
  g.nx = 9;
  g.ny = 3;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) g.values.push_back(1.0f + 0.25f * i);
  return g;
}

TEST(GridSize, EvaluatesBilinearlyAndExtendsTheBorder) {
  SizeFieldSpec spec;
  spec.terms.push_back(ramp());
  const SizeProgram size = compile_size_field(spec);
  ASSERT_EQ(size.terms.size(), 1u);
  EXPECT_FALSE(size.uniform());
  EXPECT_EQ(size.terms[0].h_min, 1.0);  // the term's bounds are its samples' range
  EXPECT_EQ(size.terms[0].h_max, 3.0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> x(0, 4), y(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p{x(rng), y(rng)};
    EXPECT_NEAR(eval_size(size.view(), p), 1 + p.x / 2, 1e-12);
  }
  EXPECT_NEAR(eval_size(size.view(), {-5, 0.5}), 1.0, 1e-12);  // left of the grid
  EXPECT_NEAR(eval_size(size.view(), {9, 7}), 3.0, 1e-12);     // beyond its far corner
  EXPECT_NEAR(eval_size(size.view(), {2, -3}), 2.0, 1e-12);    // below: column x = 2
}

TEST(GridSize, TakesTheMinimumWithTheOtherTerms) {
  SizeFieldSpec spec;
  spec.terms.push_back(UniformSize{1.5});
  spec.terms.push_back(ramp());
  DistanceSize near_circle;
  near_circle.shape = Shape{Circle{{4, 0.5}, 0.1}, "", ""};
  near_circle.h_min = 0.5;
  near_circle.slope = 1.0;
  near_circle.h_max = 5.0;
  spec.terms.push_back(near_circle);
  const SizeProgram size = compile_size_field(spec);
  for (double x = 0; x <= 4; x += 0.125) {
    const Vec2 p{x, 0.5};
    const double d = std::fabs(std::hypot(x - 4, 0.0) - 0.1);
    const double expected = std::min({1.5, 1 + x / 2, std::min(5.0, 0.5 + d)});
    EXPECT_NEAR(eval_size(size.view(), p), expected, 1e-12) << x;
  }
  const SizeRange range = size_field_range(spec);
  EXPECT_EQ(range.low, 0.5);
  EXPECT_EQ(range.high, 1.5);
}

TEST(GridSize, ScaleMultipliesTheSamples) {
  GridSize g = ramp();
  g.scale = 1e-20;  // far below what single precision holds near its smallest normal values
  SizeFieldSpec spec;
  spec.terms.push_back(g);
  const SizeProgram size = compile_size_field(spec);
  EXPECT_NEAR(eval_size(size.view(), {2, 0.5}) / 1e-20, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(size_term_range(spec.terms[0]).low, 1e-20);
}

// A unit square with h = 1 + x / 2 at h0 = 0.05: compile_problem makes the smallest value 1 (it
// is already) and the node estimate integrates 1 / h^2 = 4 / (2 + x)^2 over [0, 1]: 2 / 3.
TEST(GridSize, CompiledProblemAndNodeEstimateFollowTheGrid) {
  Problem p;
  p.geometry = Shape{Rectangle{{0, 0}, {1, 1}}, "", ""};
  GridSize g = ramp();
  g.scale = 0.5;  // h = 0.5 + x / 4: the finest edge is h0 / 2
  p.size.terms.push_back(g);
  p.h0 = 0.05;
  const CompiledProblem c = compile_problem(p);
  EXPECT_DOUBLE_EQ(c.h0, 0.025);
  EXPECT_NEAR(eval_size(c.size.view(), {1, 0.5}), 1.5, 1e-12);
  EXPECT_EQ(c.params.fscale, kGradedFscale);
  const double expected = 2 / std::sqrt(3.0) * (2.0 / 3.0) / (0.025 * 0.025);
  EXPECT_NEAR(estimate_node_count(c), expected, 0.01 * expected);
}

}  // namespace
}  // namespace meshd
