// Grid terms of the size field, the gradation and feature-size terms (both sampled into grids)
// through to_problem: each bad input fails on its field path with the allowed range; the
// request-wide limit on grid values is RESOURCE_EXHAUSTED; the size-ratio limit counts a grid's
// smallest and largest values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "client/request_file.h"
#include "core/common/error.h"
#include "tests/server/conversion_expectations.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/size_eval.cuh"
#include "server/request_conversion.h"

namespace meshd {
namespace {

using testing::expect_error;
using testing::expect_invalid;

// The unit square with a 3 x 2 grid term over it (small on the left, large on the right).
v1::MeshRequest square_with_grid() {
  return parse_request_text(
      "geometry { rectangle { min { x: 0 y: 0 } max { x: 1 y: 1 } } } h0: 0.05 "
      "size { terms { grid { nx: 3 ny: 2 origin { x: 0 y: 0 } spacing { x: 0.5 y: 1 } "
      "values: [1, 2, 4, 1, 2, 4] } } }",
      "test");
}

v1::GridSize& grid_of(v1::MeshRequest& r) {
  return *r.mutable_size()->mutable_terms(0)->mutable_grid();
}

TEST(SizeGridConversion, AValidGridBecomesAGridTerm) {
  const Problem p = to_problem(square_with_grid());
  ASSERT_EQ(p.size.terms.size(), 1u);
  const GridSize& g = std::get<GridSize>(p.size.terms[0]);
  EXPECT_EQ(g.nx, 3u);
  EXPECT_EQ(g.ny, 2u);
  EXPECT_EQ(g.spacing.x, 0.5);
  EXPECT_EQ(g.values[2], 4.0f);
  const CompiledProblem c = compile_problem(p);
  EXPECT_NEAR(c.h0 * eval_size(c.size.view(), {0.75, 0.3}), 0.05 * 3, 1e-12);
}

TEST(SizeGridConversion, EachBadFieldIsNamedWithItsRange) {
  const ErrorCode invalid = ErrorCode::kInvalidArgument;
  const std::string g = "size.terms[0].grid";
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).set_values(4, std::numeric_limits<float>::quiet_NaN());
    expect_error(r, invalid, g + ".values[4]",
                 "must be finite and > 0 (got nan); it is the sample at column i = 1, row j = 1");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).set_values(0, 0.0f);
    grid_of(r).set_values(3, -1.0f);
    expect_error(r, invalid, g + ".values[0]", "must be finite and > 0 (got 0)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).add_values(1.0f);
    expect_error(r, invalid, g + ".values",
                 "must hold nx * ny = 3 * 2 = 6 values, row by row (got 7)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).set_nx(1);
    expect_error(r, invalid, g + ".nx", "must be >= 2 (samples along that axis; got 1)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).mutable_spacing()->set_y(0);
    expect_error(r, invalid, g + ".spacing.y", "must be finite and > 0 (got 0)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).mutable_spacing()->set_x(-0.5);
    expect_error(r, invalid, g + ".spacing.x", "must be finite and > 0 (got -0.5)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).clear_spacing();
    expect_error(r, invalid, g + ".spacing", "required");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).mutable_origin()->set_x(std::numeric_limits<double>::infinity());
    expect_error(r, invalid, g + ".origin.x", "must be finite (got inf)");
  }
  {
    v1::MeshRequest r = square_with_grid();
    grid_of(r).mutable_spacing()->set_x(1e308);
    expect_error(r, invalid, g + ".spacing", "far corner");
  }
}

TEST(SizeGridConversion, TooManyValuesAreResourceExhausted) {
  ConversionLimits limits;
  limits.max_size_grid_values = 10;
  v1::MeshRequest r = square_with_grid();
  EXPECT_NO_THROW(to_problem(r, limits));
  *r.mutable_size()->add_terms() = r.size().terms(0);  // 12 values in all
  expect_error(r, ErrorCode::kResourceExhausted, "size.terms[1].grid.values",
               "may hold 10 together (earlier ones hold 6)", limits);
  // A huge nx * ny is refused for its size before its values are counted.
  v1::MeshRequest huge = square_with_grid();
  grid_of(huge).set_nx(100000);
  grid_of(huge).set_ny(100000);
  expect_error(huge, ErrorCode::kResourceExhausted, "size.terms[0].grid.values",
               "nx * ny = 10000000000 samples");
}

TEST(SizeGridConversion, TheSizeRatioCountsTheGridsRange) {
  ConversionLimits limits;
  limits.max_size_ratio = 3;  // the grid spans 1 to 4
  expect_error(square_with_grid(), ErrorCode::kInvalidArgument, "size",
               "largest h 4 from size.terms[0], smallest 1 from size.terms[0]", limits);
  v1::MeshRequest capped = square_with_grid();
  capped.mutable_size()->add_terms()->mutable_uniform()->set_value(2);  // min(grid, 2): 1 to 2
  EXPECT_NO_THROW(to_problem(capped, limits));
}

TEST(SizeGridConversion, GradationRangeAndItsGrid) {
  v1::MeshRequest r = square_with_grid();
  for (double bad : {-1.0, 11.0, std::numeric_limits<double>::quiet_NaN()}) {
    r.mutable_size()->set_gradation(bad);
    expect_error(r, ErrorCode::kInvalidArgument, "size.gradation",
                 "must be 0 (none) or in (0, 10]");
  }
  r.mutable_size()->set_gradation(0);
  EXPECT_TRUE(std::holds_alternative<GridSize>(to_problem(r).size.terms[0]));
  // The limited grid replaces the terms. A gradation of 0.5 leaves the grid's own growth (an
  // edge of 0.05 * (1 + 2x), then 0.05 * 4x) as it is; one of 0.02 bounds it.
  r.mutable_size()->set_gradation(0.5);
  const Problem p = to_problem(r);
  ASSERT_EQ(p.size.terms.size(), 1u);
  EXPECT_EQ(p.size.gradation, 0.0);
  const CompiledProblem c = compile_problem(p);
  auto edge = [&](double x) { return c.h0 * eval_size(c.size.view(), {x, 0.5}); };
  EXPECT_NEAR(edge(0.0), 0.05, 1e-6);
  EXPECT_NEAR(edge(0.1), 0.05 * 1.2, 1e-6);
  r.mutable_size()->set_gradation(0.02);
  const CompiledProblem slow = compile_problem(to_problem(r));
  EXPECT_NEAR(slow.h0 * eval_size(slow.size.view(), {1.0, 0.5}), 0.05 + 0.02 * 1.0, 1e-5);
}

TEST(SizeGridConversion, FeatureTermRangesAndItsGrid) {
  const std::string channel =
      "geometry { rectangle { min { x: 0 y: 0 } max { x: 8 y: 1 } } } h0: 0.05 ";
  auto request = [&](const std::string& feature) {
    return parse_request_text(channel + "size { terms { feature { " + feature + " } } }", "test");
  };
  const ErrorCode invalid = ErrorCode::kInvalidArgument;
  const std::string f = "size.terms[0].feature";
  expect_error(request("elements: 0.5 h_min: 1 h_max: 2"), invalid, f + ".elements",
               "must be in [1, 1000], edges across a narrow part (got 0.5)");
  expect_error(request("elements: 4 h_min: 0 h_max: 2"), invalid, f + ".h_min",
               "must be finite and > 0 (got 0)");
  expect_error(request("elements: 4 h_min: 2 h_max: 1"), invalid, f + ".h_max",
               "must be finite and >= h_min = 2 (got 1)");
  ConversionLimits limits;
  limits.max_size_ratio = 10;
  expect_error(request("elements: 4 h_min: 1 h_max: 20"), invalid, "size", "at most 10 allowed",
               limits);
  // Converted, it is already a grid: 4 elements across the width of 1.
  const Problem p = to_problem(request("elements: 4 h_min: 1 h_max: 10"));
  ASSERT_EQ(p.size.terms.size(), 1u);
  ASSERT_TRUE(std::holds_alternative<GridSize>(p.size.terms[0]));
  const CompiledProblem c = compile_problem(p);
  EXPECT_NEAR(c.h0 * eval_size(c.size.view(), {4, 0.5}), 0.25, 0.01);
}

}  // namespace
}  // namespace meshd
