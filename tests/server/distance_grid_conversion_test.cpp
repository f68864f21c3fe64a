// DistanceGrid shapes through to_problem: every class of bad grid names its field, a grid too
// large for the limit is RESOURCE_EXHAUSTED, and a good one arrives as sampled.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "core/common/error.h"
#include "tests/server/conversion_expectations.h"
#include "server/request_conversion.h"

namespace meshd {
namespace {

using testing::expect_error;
using testing::expect_invalid;

// The unit disk's distance on an n x n grid over [-1.5, 1.5]^2, at h0 0.1.
v1::MeshRequest disk_grid_request(uint32_t n = 31) {
  v1::MeshRequest request;
  request.set_h0(0.1);
  auto* g = request.mutable_geometry()->mutable_distance_grid();
  g->set_nx(n);
  g->set_ny(n);
  g->mutable_origin()->set_x(-1.5);
  g->mutable_origin()->set_y(-1.5);
  g->mutable_spacing()->set_x(3.0 / (n - 1));
  g->mutable_spacing()->set_y(3.0 / (n - 1));
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i)
      g->add_values(static_cast<float>(
          std::hypot(-1.5 + i * g->spacing().x(), -1.5 + j * g->spacing().y()) - 1));
  return request;
}

v1::DistanceGrid& grid_of(v1::MeshRequest& r) {
  return *r.mutable_geometry()->mutable_distance_grid();
}

TEST(DistanceGridConversion, AGoodGridArrivesAsSampled) {
  const Problem p = to_problem(disk_grid_request());
  const auto& g = std::get<DistanceGrid>(p.geometry.node);
  EXPECT_EQ(g.nx, 31u);
  EXPECT_EQ(g.ny, 31u);
  EXPECT_DOUBLE_EQ(g.origin.x, -1.5);
  EXPECT_DOUBLE_EQ(g.spacing.y, 0.1);
  ASSERT_EQ(g.values.size(), 31u * 31u);
  EXPECT_EQ(g.values[15 * 31 + 15], -1.0f);  // the centre, row 15, column 15
  EXPECT_EQ(p.geometry.path, "geometry");
}

TEST(DistanceGridConversion, TooFewSamplesAlongAnAxis) {
  v1::MeshRequest r = disk_grid_request();
  grid_of(r).set_nx(1);
  expect_invalid(r, "geometry.distance_grid.nx", "must be >= 2");
  r = disk_grid_request();
  grid_of(r).set_ny(0);
  expect_invalid(r, "geometry.distance_grid.ny", "must be >= 2");
}

TEST(DistanceGridConversion, WrongValueCount) {
  v1::MeshRequest r = disk_grid_request();
  grid_of(r).mutable_values()->RemoveLast();
  expect_invalid(r, "geometry.distance_grid.values", "must hold nx * ny = 31 * 31 = 961 values");
  r = disk_grid_request();
  grid_of(r).set_nx(30);
  expect_invalid(r, "geometry.distance_grid.values", "(got 961)");
}

TEST(DistanceGridConversion, NonFiniteValueNamesTheFirstBadIndex) {
  v1::MeshRequest r = disk_grid_request();
  grid_of(r).set_values(40, std::numeric_limits<float>::quiet_NaN());
  grid_of(r).set_values(50, std::numeric_limits<float>::infinity());
  expect_invalid(r, "geometry.distance_grid.values[40]",
                 "must be finite (got nan); sample (i, j) = (9, 1)");
}

TEST(DistanceGridConversion, BadSpacingAndOrigin) {
  v1::MeshRequest r = disk_grid_request();
  grid_of(r).mutable_spacing()->set_x(0);
  expect_invalid(r, "geometry.distance_grid.spacing.x", "must be finite and > 0 (got 0)");
  r = disk_grid_request();
  grid_of(r).mutable_spacing()->set_y(-0.1);
  expect_invalid(r, "geometry.distance_grid.spacing.y", "must be finite and > 0 (got -0.1)");
  r = disk_grid_request();
  grid_of(r).mutable_spacing()->set_y(std::numeric_limits<double>::infinity());
  expect_invalid(r, "geometry.distance_grid.spacing.y", "(got inf)");
  r = disk_grid_request();
  grid_of(r).mutable_origin()->set_y(std::nan(""));
  expect_invalid(r, "geometry.distance_grid.origin.y", "must be finite (got nan)");
  r = disk_grid_request();
  grid_of(r).mutable_spacing()->set_x(1e307);
  expect_invalid(r, "geometry.distance_grid.spacing", "far corner");
}

TEST(DistanceGridConversion, NoNegativeValueIsAnEmptyDomain) {
  v1::MeshRequest r = disk_grid_request();
  for (float& v : *grid_of(r).mutable_values()) v = std::fabs(v) + 0.01f;
  expect_invalid(r, "geometry.distance_grid.values", "has no value < 0");
}

TEST(DistanceGridConversion, SamplesAboveTheLimitAreResourceExhausted) {
  ConversionLimits limits;
  limits.max_grid_samples = 961;
  EXPECT_NO_THROW(to_problem(disk_grid_request(), limits));
  limits.max_grid_samples = 960;
  expect_error(disk_grid_request(), ErrorCode::kResourceExhausted, "geometry.distance_grid.values",
               "may hold 960 together", limits);
  // nx * ny counts, not the values sent: a header that claims 10^10 samples is refused before
  // anything is read or allocated for it.
  v1::MeshRequest huge = disk_grid_request();
  grid_of(huge).set_nx(100'000);
  grid_of(huge).set_ny(100'000);
  expect_error(huge, ErrorCode::kResourceExhausted, "geometry.distance_grid.values",
               "nx * ny = 10000000000 samples");
  // The limit is on all the grids of a tree together, and named at the grid that crosses it.
  v1::MeshRequest two;
  two.set_h0(0.1);
  auto* shapes = two.mutable_geometry()->mutable_union_()->mutable_shapes();
  *shapes->Add() = disk_grid_request().geometry();
  *shapes->Add() = disk_grid_request().geometry();
  limits.max_grid_samples = 1500;
  expect_error(two, ErrorCode::kResourceExhausted, "geometry.union.shapes[1].distance_grid.values",
               "may hold 1500 together (earlier ones hold 961)", limits);
}

TEST(DistanceGridConversion, TransformedAndNamedLikeOtherShapes) {
  v1::MeshRequest r;
  r.set_h0(0.1);
  auto* scale = r.mutable_geometry()->mutable_scale();
  scale->set_factor(2);
  *scale->mutable_shape() = disk_grid_request().geometry();
  scale->mutable_shape()->set_name("organ");
  const Problem p = to_problem(r);
  const auto& t = std::get<Transformed>(p.geometry.node);
  EXPECT_DOUBLE_EQ(t.transform.scale, 2.0);
  EXPECT_EQ(t.operand.at(0).name, "organ");
  EXPECT_TRUE(std::holds_alternative<DistanceGrid>(t.operand.at(0).node));
}

}  // namespace
}  // namespace meshd
