#include "server/request_conversion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "client/request_file.h"
#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/node_estimate.h"
#include "tests/server/conversion_expectations.h"

namespace meshd {
namespace {

using testing::expect_error;
using testing::expect_invalid;

// ---------------------------------------------------------------------------------------------
// Helpers: requests are written in text format, as users write them.

v1::MeshRequest parse(const std::string& text) { return parse_request_text(text, "test"); }

// A valid request (G1 at a coarse h0) with `extra` merged in: its fields add to the request, or
// replace the value of a singular one (h0).
v1::MeshRequest disk_with(const std::string& extra) {
  v1::MeshRequest request = parse("geometry { circle { radius: 1 } } h0: 0.1");
  request.MergeFrom(parse(extra));
  return request;
}

void expect_invalid(const std::string& text, const std::string& field, const std::string& message,
                    const ConversionLimits& limits = {}) {
  SCOPED_TRACE(text);
  expect_invalid(parse(text), field, message, limits);
}

// ---------------------------------------------------------------------------------------------
// One test per class of bad input.

TEST(RequestConversion, MissingGeometry) { expect_invalid("h0: 0.1", "geometry", "required"); }

TEST(RequestConversion, ShapeWithNoKind) {
  expect_invalid("geometry { name: \"a\" } h0: 0.1", "geometry", "set exactly one of circle,");
  expect_invalid("geometry { union { shapes { circle { radius: 1 } } shapes { } } } h0: 0.1",
                 "geometry.union.shapes[1]", "set exactly one of");
}

TEST(RequestConversion, NonFiniteNumbers) {
  expect_invalid("geometry { circle { center { x: nan } radius: 1 } } h0: 0.1",
                 "geometry.circle.center.x", "must be finite (got nan)");
  expect_invalid("geometry { rectangle { min { x: 0 y: -inf } max { x: 1 y: 1 } } } h0: 0.1",
                 "geometry.rectangle.min.y", "must be finite (got -inf)");
  expect_invalid("geometry { ellipse { center { y: inf } semi_axis_x: 1 semi_axis_y: 1 } } h0: 1",
                 "geometry.ellipse.center.y", "must be finite (got inf)");
  expect_invalid(
      "geometry { polygon { vertices { x: 0 y: 0 } vertices { x: 1 y: nan } vertices { x: 0 y: 1 "
      "} } } h0: 0.1",
      "geometry.polygon.vertices[1].y", "must be finite (got nan)");
  expect_invalid("geometry { half_plane { normal { x: 1 } offset: inf } } h0: 0.1",
                 "geometry.half_plane.offset", "must be finite (got inf)");
  expect_invalid("geometry { translate { offset { x: inf } shape { circle { radius: 1 } } } }",
                 "geometry.translate.offset.x", "must be finite (got inf)");
  expect_invalid("geometry { rotate { angle_deg: nan shape { circle { radius: 1 } } } }",
                 "geometry.rotate.angle_deg", "must be finite (got nan)");
  expect_invalid(
      "geometry { rotate { angle_deg: 1 center { y: -inf } shape { circle { radius: 1 } } } }",
      "geometry.rotate.center.y", "must be finite (got -inf)");
  expect_invalid(
      "geometry { scale { factor: 2 center { x: nan } shape { circle { radius: 1 } } } }",
      "geometry.scale.center.x", "must be finite (got nan)");
  expect_invalid(disk_with("size { terms { distance { shape { circle { radius: 1 } } h_min: 1 "
                           "slope: inf h_max: 2 } } }"),
                 "size.terms[0].distance.slope", "must be finite and >= 0 (got inf)");
}

TEST(RequestConversion, RadiusAndSemiAxesMustBePositive) {
  expect_invalid("geometry { circle { radius: 0 } } h0: 0.1", "geometry.circle.radius",
                 "must be finite and > 0 (got 0)");
  expect_invalid("geometry { circle { radius: -1 } } h0: 0.1", "geometry.circle.radius",
                 "must be finite and > 0 (got -1)");
  expect_invalid("geometry { circle { radius: inf } } h0: 0.1", "geometry.circle.radius",
                 "must be finite and > 0 (got inf)");
  expect_invalid("geometry { ellipse { semi_axis_x: 0 semi_axis_y: 1 } } h0: 0.1",
                 "geometry.ellipse.semi_axis_x", "must be finite and > 0 (got 0)");
  expect_invalid("geometry { ellipse { semi_axis_x: 1 semi_axis_y: -2 } } h0: 0.1",
                 "geometry.ellipse.semi_axis_y", "must be finite and > 0 (got -2)");
}

TEST(RequestConversion, RectangleMinMustBeBelowMax) {
  expect_invalid("geometry { rectangle { min { x: 1 y: 0 } max { x: 1 y: 1 } } } h0: 0.1",
                 "geometry.rectangle.max.x", "must be > min.x = 1 (got 1)");
  expect_invalid("geometry { rectangle { min { x: 0 y: 0 } max { x: 1 y: -0.5 } } } h0: 0.1",
                 "geometry.rectangle.max.y", "must be > min.y = 0 (got -0.5)");
}

TEST(RequestConversion, PolygonWithFewerThanThreeVertices) {
  expect_invalid("geometry { polygon { vertices { x: 0 } vertices { x: 1 } } } h0: 0.1",
                 "geometry.polygon.vertices", "at least 3 vertices (got 2)");
}

TEST(RequestConversion, PolygonSelfIntersecting) {
  expect_invalid(
      "geometry { difference { base { circle { radius: 3 } } subtract { polygon { "
      "vertices { x: 0 y: 0 } vertices { x: 1 y: 1 } vertices { x: 1 y: 0 } vertices { x: 0 y: 1 "
      "} } } } } h0: 0.1",
      "geometry.difference.subtract[0].polygon.vertices", "edges 0 and 2 cross near (0.5, 0.5)");
}

TEST(RequestConversion, PolygonWithZeroArea) {
  expect_invalid(
      "geometry { polygon { vertices { x: 0 } vertices { x: 1 } vertices { x: 2 } } } h0: 0.1",
      "geometry.polygon.vertices", "zero area");
}

TEST(RequestConversion, PolygonWithTooManyVertices) {
  ConversionLimits limits;
  limits.max_polygon_vertices = 4;
  expect_invalid(
      "geometry { polygon { vertices { x: 0 y: 0 } vertices { x: 1 y: 0 } vertices { x: 2 y: 1 } "
      "vertices { x: 1 y: 2 } vertices { x: 0 y: 1 } } } h0: 0.1",
      "geometry.polygon.vertices", "at most 4 vertices allowed (got 5)", limits);
}

TEST(RequestConversion, HalfPlaneWithZeroNormal) {
  expect_invalid("geometry { half_plane { offset: 1 } } h0: 0.1 bbox { max { x: 1 y: 1 } }",
                 "geometry.half_plane.normal", "must be non-zero");
}

TEST(RequestConversion, UnionAndIntersectionNeedShapes) {
  expect_invalid("geometry { union { } } h0: 0.1", "geometry.union.shapes",
                 "needs at least 1 shape (got 0)");
  expect_invalid("geometry { intersection { } } h0: 0.1", "geometry.intersection.shapes",
                 "needs at least 1 shape (got 0)");
}

TEST(RequestConversion, DifferenceNeedsBase) {
  expect_invalid("geometry { difference { subtract { circle { radius: 1 } } } } h0: 0.1",
                 "geometry.difference.base", "required");
}

TEST(RequestConversion, TransformsNeedShape) {
  expect_invalid("geometry { translate { offset { x: 1 } } } h0: 0.1", "geometry.translate.shape",
                 "required");
  expect_invalid("geometry { rotate { angle_deg: 10 } } h0: 0.1", "geometry.rotate.shape",
                 "required");
  expect_invalid("geometry { scale { factor: 2 } } h0: 0.1", "geometry.scale.shape", "required");
}

TEST(RequestConversion, ScaleFactorMustBePositive) {
  expect_invalid("geometry { scale { factor: 0 shape { circle { radius: 1 } } } } h0: 0.1",
                 "geometry.scale.factor", "must be finite and > 0 (got 0)");
  expect_invalid("geometry { scale { factor: -2 shape { circle { radius: 1 } } } } h0: 0.1",
                 "geometry.scale.factor", "must be finite and > 0 (got -2)");
}

// `levels` nested translates around a unit circle: a tree of depth levels + 1.
v1::MeshRequest nested(int levels) {
  v1::MeshRequest request;
  request.set_h0(0.1);
  v1::Shape* shape = request.mutable_geometry();
  for (int i = 0; i < levels; ++i) shape = shape->mutable_translate()->mutable_shape();
  shape->mutable_circle()->set_radius(1);
  return request;
}

TEST(RequestConversion, TreeTooDeep) {
  EXPECT_NO_THROW(to_problem(nested(31)));  // depth 32
  std::string path = "geometry";
  for (int i = 0; i < 32; ++i) path += ".translate.shape";
  expect_invalid(nested(32), path, "deeper than the limit of 32 levels");
}

TEST(RequestConversion, TreeTooLarge) {
  ConversionLimits limits;
  limits.max_tree_nodes = 5;
  const std::string two = "shapes { circle { radius: 1 } } shapes { circle { radius: 1 } } ";
  // A union of 4 circles is 5 nodes: at the limit.
  EXPECT_NO_THROW(to_problem(parse("geometry { union { " + two + two + " } } h0: 0.1"), limits));
  expect_invalid("geometry { union { " + two + two + "shapes { circle { radius: 1 } } } } h0: 0.1",
                 "geometry", "more than the limit of 5 shape nodes", limits);
  // A size term's shape is a tree of its own, named by its own path.
  expect_invalid(disk_with("size { terms { distance { shape { union { " + two + two + two +
                           "} } h_min: 1 h_max: 1 } } }"),
                 "size.terms[0].distance.shape", "more than the limit of 5 shape nodes", limits);
}

TEST(RequestConversion, H0MustBeFiniteAndPositive) {
  for (const char* h0 : {"0", "-0.1", "nan", "inf"}) {
    expect_invalid(std::string("geometry { circle { radius: 1 } } h0: ") + h0, "h0",
                   std::string("must be finite and > 0 (got ") + h0 + ")");
  }
  expect_invalid("geometry { circle { radius: 1 } }", "h0", "must be finite and > 0 (got 0)");
}

TEST(RequestConversion, SizeTermsOutOfRange) {
  const std::string circle = "shape { circle { radius: 0.5 } } ";
  expect_invalid(disk_with("size { terms { uniform { value: 0 } } }"),
                 "size.terms[0].uniform.value", "must be finite and > 0 (got 0)");
  expect_invalid(disk_with("size { terms { uniform { value: 1 } } terms { distance { " + circle +
                           "h_min: 0 h_max: 1 } } }"),
                 "size.terms[1].distance.h_min", "must be finite and > 0 (got 0)");
  expect_invalid(
      disk_with("size { terms { distance { " + circle + "h_min: 1 slope: -1 h_max: 2 } } }"),
      "size.terms[0].distance.slope", "must be finite and >= 0 (got -1)");
  expect_invalid(
      disk_with("size { terms { distance { " + circle + "h_min: 1 slope: 1 h_max: 0.5 } } }"),
      "size.terms[0].distance.h_max", "must be finite and >= h_min = 1 (got 0.5)");
  expect_invalid(disk_with("size { terms { uniform { value: 1 } } terms { } }"), "size.terms[1]",
                 "set exactly one of uniform, distance");
  expect_invalid(disk_with("size { terms { distance { h_min: 1 h_max: 1 } } }"),
                 "size.terms[0].distance.shape", "required");
  // The term's shape is checked like the geometry, with its own paths.
  expect_invalid(disk_with("size { terms { distance { shape { union { shapes { circle { radius: "
                           "-1 } } } } h_min: 1 h_max: 1 } } }"),
                 "size.terms[0].distance.shape.union.shapes[0].circle.radius",
                 "must be finite and > 0 (got -1)");
}

TEST(RequestConversion, SizeRatioBeyondLimit) {
  const std::string graded =
      "terms { distance { shape { circle { radius: 0.5 } } h_min: 0.5 slope: 1 h_max: 600 } } ";
  expect_invalid(disk_with("size { " + graded + "}"), "size",
                 "factor up to 1200 (largest h 600 from size.terms[0], smallest 0.5 from "
                 "size.terms[0]); at most 1000 allowed");
  // A uniform term caps h (h is the minimum of the terms): the ratio bound drops to 4.
  EXPECT_NO_THROW(to_problem(disk_with("size { " + graded + "terms { uniform { value: 2 } } }")));
  // Uniform terms alone: the smallest value is the field.
  EXPECT_NO_THROW(to_problem(disk_with("size { terms { uniform { value: 0.001 } } terms { "
                                       "uniform { value: 5 } } }"),
                             ConversionLimits{.max_nodes = 1'000'000'000'000}));
  ConversionLimits limits;
  limits.max_size_ratio = 2;
  expect_invalid(disk_with("size { terms { distance { shape { circle { radius: 0.5 } } h_min: 1 "
                           "slope: 4 h_max: 2.5 } } }"),
                 "size", "at most 2 allowed", limits);
}

TEST(RequestConversion, TooManySizeTerms) {
  ConversionLimits limits;
  limits.max_size_terms = 1;
  expect_invalid(
      disk_with("size { terms { uniform { value: 1 } } terms { uniform { value: 1 } } }"),
      "size.terms", "at most 1 terms allowed (got 2)", limits);
}

TEST(RequestConversion, BoundingBox) {
  expect_invalid(disk_with("bbox { min { x: -1 y: 1 } max { x: 1 y: 1 } }"), "bbox.max.y",
                 "must be > min.y = 1 (got 1)");
  expect_invalid(disk_with("bbox { min { x: 2 y: -1 } max { x: 1 y: 1 } }"), "bbox.max.x",
                 "must be > min.x = 2 (got 1)");
  expect_invalid(disk_with("bbox { min { x: -inf y: -1 } max { x: 1 y: 1 } }"), "bbox.min.x",
                 "must be finite (got -inf)");
}

TEST(RequestConversion, ParamsOutOfRange) {
  struct Case {
    const char* text;
    const char* field;
    const char* range;
  };
  const Case cases[] = {
      {"dptol: 0", "params.dptol", "must be in (0, 0.1] (got 0)"},
      {"dptol: 0.2", "params.dptol", "must be in (0, 0.1] (got 0.2)"},
      {"ttol: 1.5", "params.ttol", "must be in (0, 1] (got 1.5)"},
      {"ttol: -0.1", "params.ttol", "must be in (0, 1] (got -0.1)"},
      {"fscale: 0.9", "params.fscale", "must be in [1, 2] (got 0.9)"},
      {"fscale: 2.5", "params.fscale", "must be in [1, 2] (got 2.5)"},
      {"deltat: 0.6", "params.deltat", "must be in (0, 0.5] (got 0.6)"},
      {"deltat: nan", "params.deltat", "must be in (0, 0.5] (got nan)"},
      {"geps: 0", "params.geps", "must be in (0, 0.1] (got 0)"},
      {"geps: inf", "params.geps", "must be in (0, 0.1] (got inf)"},
      {"density_control_interval: 1001", "params.density_control_interval",
       "must be in [0, 1000] (got 1001)"},
      {"max_iterations: 0", "params.max_iterations", "must be in [1, 1000000] (got 0)"},
      {"max_iterations: 1000001", "params.max_iterations", "must be in [1, 1000000] (got 1000001)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    expect_invalid(disk_with(std::string("params { ") + c.text + " }"), c.field, c.range);
  }
  // The ends of the closed ranges are allowed.
  EXPECT_NO_THROW(to_problem(disk_with(
      "params { dptol: 0.1 ttol: 1 fscale: 2 deltat: 0.5 geps: 0.1 density_control_interval: 0 "
      "max_iterations: 1 }")));
  EXPECT_NO_THROW(to_problem(
      disk_with("params { fscale: 1 density_control_interval: 1000 max_iterations: 1000000 }")));
}

TEST(RequestConversion, FixedPoints) {
  expect_invalid(disk_with("fixed_points { x: 0 } fixed_points { y: 0.5 } fixed_points { x: nan }"),
                 "fixed_points[2].x", "must be finite (got nan)");
  expect_invalid(disk_with("fixed_points { y: -inf }"), "fixed_points[0].y",
                 "must be finite (got -inf)");
  ConversionLimits limits;
  limits.max_fixed_points = 1;
  expect_invalid(disk_with("fixed_points { x: 0 } fixed_points { y: 0.5 }"), "fixed_points",
                 "at most 1 fixed points allowed (got 2)", limits);
}

TEST(RequestConversion, Names) {
  expect_invalid("geometry { name: \"outer wall\" circle { radius: 1 } } h0: 0.1", "geometry.name",
                 "character 5 (' ') is not allowed; a name is 1 to 64 letters, digits, '_', '-' "
                 "or '.'");
  expect_invalid(
      "geometry { union { shapes { name: \"caf\\303\\251\" circle { radius: 1 } } } } "
      "h0: 0.1",
      "geometry.union.shapes[0].name", "character 3 (0xc3) is not allowed");
  expect_invalid("geometry { name: \"" + std::string(65, 'a') + "\" circle { radius: 1 } } h0: 0.1",
                 "geometry.name", "is 65 characters long; a name is 1 to 64");
  EXPECT_NO_THROW(to_problem(
      parse("geometry { name: \"" + std::string(64, 'a') + "\" circle { radius: 1 } } h0: 0.1")));
  EXPECT_NO_THROW(
      to_problem(parse("geometry { name: \"Outer-wall_2.v1\" circle { radius: 1 } } h0: 0.1")));
}

// ---------------------------------------------------------------------------------------------
// The estimated node count (needs estimate_node_count).

TEST(RequestConversion, TooManyNodesIsResourceExhausted) {
  // The unit disk at h0 = 1e-4 has about 3.6e8 nodes.
  expect_error(disk_with("h0: 1e-4"), ErrorCode::kResourceExhausted, "h0",
               "nodes, more than the limit of 5000000: h0 must be at least about 0.000");
  ConversionLimits limits;
  limits.max_nodes = 1000;
  expect_error(disk_with("h0: 0.04"), ErrorCode::kResourceExhausted, "h0",
               "more than the limit of 1000", limits);
}

TEST(RequestConversion, TooFewNodes) {
  expect_invalid(disk_with("h0: 10"), "h0", "at least 3 are needed: h0 must be at most about");
}

TEST(RequestConversion, EmptyDomain) {
  expect_invalid(
      "geometry { intersection { shapes { circle { center { x: -2 } radius: 1 } } "
      "shapes { circle { center { x: 2 } radius: 1 } } } } h0: 0.1",
      "geometry", "empty");
}

TEST(RequestConversion, UnboundedGeometryNeedsBbox) {
  expect_invalid("geometry { half_plane { normal { x: 1 } } } h0: 0.1", "bbox", "required");
  EXPECT_NO_THROW(
      to_problem(parse("geometry { half_plane { normal { x: 1 } } } h0: 0.1 "
                       "bbox { min { x: -1 y: -1 } max { x: 1 y: 1 } }")));
}

// ---------------------------------------------------------------------------------------------
// Good conversions.

template <typename T>
const T& node(const Shape& shape) {
  const T* value = std::get_if<T>(&shape.node);
  if (value == nullptr) throw std::runtime_error(shape.path + " has another node type");
  return *value;
}

void expect_near(Vec2 actual, Vec2 expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-12);
  EXPECT_NEAR(actual.y, expected.y, 1e-12);
}

TEST(RequestConversion, TransformsAreSimilaritiesAboutTheirCenter) {
  const Problem p = to_problem(parse(R"pb(
    geometry {
      rotate {
        angle_deg: 90
        center { x: 1 y: 0 }
        shape {
          scale {
            factor: 2
            center { x: 1 y: 1 }
            shape {
              translate {
                offset { x: 3 y: 4 }
                shape { circle { radius: 0.25 } }
              }
            }
          }
        }
      }
    }
    h0: 0.05
  )pb"));
  const Transformed& rotate = node<Transformed>(p.geometry);
  EXPECT_EQ(p.geometry.path, "geometry");
  EXPECT_DOUBLE_EQ(rotate.transform.angle, std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(rotate.transform.scale, 1.0);
  // Rotating about (1, 0): the center stays, (2, 0) goes to (1, 1).
  expect_near(apply(rotate.transform, {1, 0}), {1, 0});
  expect_near(apply(rotate.transform, {2, 0}), {1, 1});

  const Shape& scaled = rotate.operand.at(0);
  EXPECT_EQ(scaled.path, "geometry.rotate.shape");
  const Transformed& scale = node<Transformed>(scaled);
  EXPECT_DOUBLE_EQ(scale.transform.scale, 2.0);
  EXPECT_DOUBLE_EQ(scale.transform.angle, 0.0);
  expect_near(apply(scale.transform, {1, 1}), {1, 1});
  expect_near(apply(scale.transform, {2, 1}), {3, 1});

  const Shape& translated = scale.operand.at(0);
  EXPECT_EQ(translated.path, "geometry.rotate.shape.scale.shape");
  const Transformed& translate = node<Transformed>(translated);
  expect_near(apply(translate.transform, {0, 0}), {3, 4});
  EXPECT_DOUBLE_EQ(translate.transform.scale, 1.0);
  EXPECT_DOUBLE_EQ(translate.transform.angle, 0.0);

  const Shape& circle = translate.operand.at(0);
  EXPECT_EQ(circle.path, "geometry.rotate.shape.scale.shape.translate.shape");
  EXPECT_DOUBLE_EQ(node<Circle>(circle).radius, 0.25);

  // The whole chain: the circle's center (0,0) -> (3,4) -> 2((3,4)-(1,1))+(1,1) = (5,7)
  // -> rotated 90 degrees about (1,0): (1,0) + R90 (4,7) = (1,0) + (-7,4) = (-6,4).
  const Similarity all = compose(rotate.transform, compose(scale.transform, translate.transform));
  expect_near(apply(all, {0, 0}), {-6, 4});
}

TEST(RequestConversion, NamesPropagateToUnnamedPrimitives) {
  const Problem p = to_problem(parse(R"pb(
    geometry {
      difference {
        base {
          name: "walls"
          union {
            shapes {
              rectangle {
                min { x: -2 y: -1 }
                max { x: 0 y: 1 }
              }
            }
            shapes {
              name: "door"
              rectangle {
                min { x: -0.5 y: -0.5 }
                max { x: 2 y: 0.5 }
              }
            }
            shapes {
              translate {
                offset { x: 1 }
                shape { circle { radius: 1 } }
              }
            }
          }
        }
        subtract { circle { radius: 0.2 } }
      }
    }
    h0: 0.05
  )pb"));
  const Csg& difference = node<Csg>(p.geometry);
  EXPECT_EQ(difference.op, CsgOp::kDifference);
  EXPECT_EQ(p.geometry.name, "");
  const Shape& walls = difference.operands.at(0);
  EXPECT_EQ(walls.name, "walls");
  EXPECT_EQ(walls.path, "geometry.difference.base");
  const Csg& parts = node<Csg>(walls);
  EXPECT_EQ(parts.op, CsgOp::kUnion);
  ASSERT_EQ(parts.operands.size(), 3u);
  EXPECT_EQ(parts.operands[0].name, "walls");
  EXPECT_EQ(parts.operands[0].path, "geometry.difference.base.union.shapes[0]");
  EXPECT_EQ(parts.operands[1].name, "door");
  const Shape& moved = parts.operands[2];
  EXPECT_EQ(moved.name, "walls");
  EXPECT_EQ(node<Transformed>(moved).operand.at(0).name, "walls");
  // No named ancestor: left empty for the geometry compiler's "<kind><index>".
  const Shape& hole = difference.operands.at(1);
  EXPECT_EQ(hole.name, "");
  EXPECT_EQ(hole.path, "geometry.difference.subtract[0]");
}

TEST(RequestConversion, ParamsDefaultsAndValues) {
  const Problem defaults = to_problem(disk_with(""));
  const Params core_defaults;
  EXPECT_EQ(defaults.params.dptol, core_defaults.dptol);
  EXPECT_EQ(defaults.params.ttol, core_defaults.ttol);
  EXPECT_EQ(defaults.params.fscale, core_defaults.fscale);
  EXPECT_EQ(defaults.params.deltat, core_defaults.deltat);
  EXPECT_EQ(defaults.params.geps, core_defaults.geps);
  EXPECT_EQ(defaults.params.density_control_interval, core_defaults.density_control_interval);
  EXPECT_EQ(defaults.params.max_iterations, core_defaults.max_iterations);
  EXPECT_EQ(defaults.params.cleanup, core_defaults.cleanup);
  EXPECT_TRUE(defaults.auto_corners);
  EXPECT_FALSE(defaults.bbox.has_value());
  EXPECT_TRUE(defaults.size.terms.empty());

  const Problem set = to_problem(disk_with(
      "params { dptol: 0.01 ttol: 0.2 fscale: 1.5 deltat: 0.1 geps: 0.01 "
      "density_control_interval: 0 max_iterations: 500 cleanup: false } auto_corners: false "
      "seed: 42 fixed_points { x: 0.5 y: -0.25 } bbox { min { x: -2 y: -2 } max { x: 2 y: 2 } }"));
  EXPECT_EQ(set.params.dptol, 0.01);
  EXPECT_EQ(set.params.ttol, 0.2);
  EXPECT_EQ(set.params.fscale, 1.5);
  EXPECT_EQ(set.params.deltat, 0.1);
  EXPECT_EQ(set.params.geps, 0.01);
  EXPECT_EQ(set.params.density_control_interval, 0);
  EXPECT_EQ(set.params.max_iterations, 500);
  EXPECT_FALSE(set.params.cleanup);
  EXPECT_EQ(set.params.deps, core_defaults.deps);  // not in the API
  EXPECT_FALSE(set.auto_corners);
  EXPECT_EQ(set.seed, 42u);
  ASSERT_EQ(set.fixed_points.size(), 1u);
  EXPECT_EQ(set.fixed_points[0], (Vec2{0.5, -0.25}));
  ASSERT_TRUE(set.bbox.has_value());
  EXPECT_EQ(set.bbox->min, (Vec2{-2, -2}));
  EXPECT_EQ(set.bbox->max, (Vec2{2, 2}));
  EXPECT_EQ(set.h0, 0.1);
}

// ---------------------------------------------------------------------------------------------
// The example files: G1-G5 of geometries.md.

Problem example(const std::string& file) {
  return to_problem(read_request_file(std::string(MESHD_SOURCE_DIR) + "/examples/" + file));
}

// The CI examples are sized for about 1,500 to 3,000 nodes.
void expect_ci_size(const Problem& p) {
  const double nodes = estimate_node_count(p);
  EXPECT_GE(nodes, 1500);
  EXPECT_LE(nodes, 3000);
}

void expect_square_with_hole(const Shape& geometry) {
  const Csg& difference = node<Csg>(geometry);
  EXPECT_EQ(difference.op, CsgOp::kDifference);
  ASSERT_EQ(difference.operands.size(), 2u);
  const Shape& outer = difference.operands[0];
  EXPECT_EQ(outer.name, "outer");
  EXPECT_EQ(outer.path, "geometry.difference.base");
  EXPECT_EQ(node<Rectangle>(outer).min, (Vec2{-1, -1}));
  EXPECT_EQ(node<Rectangle>(outer).max, (Vec2{1, 1}));
  const Shape& hole = difference.operands[1];
  EXPECT_EQ(hole.name, "hole");
  EXPECT_EQ(hole.path, "geometry.difference.subtract[0]");
  EXPECT_EQ(node<Circle>(hole).center, (Vec2{0, 0}));
  EXPECT_EQ(node<Circle>(hole).radius, 0.5);
}

TEST(RequestConversionExamples, G1Disk) {
  const Problem p = example("g1_disk.textproto");
  EXPECT_EQ(p.geometry.name, "outer");
  EXPECT_EQ(node<Circle>(p.geometry).center, (Vec2{0, 0}));
  EXPECT_EQ(node<Circle>(p.geometry).radius, 1.0);
  EXPECT_TRUE(p.size.terms.empty());
  EXPECT_TRUE(p.fixed_points.empty());
  expect_ci_size(p);
}

TEST(RequestConversionExamples, G2SquareWithHole) {
  const Problem p = example("g2_square_hole.textproto");
  expect_square_with_hole(p.geometry);
  EXPECT_TRUE(p.size.terms.empty());
  EXPECT_TRUE(p.auto_corners);  // the 4 square corners
  EXPECT_TRUE(p.fixed_points.empty());
  expect_ci_size(p);
}

TEST(RequestConversionExamples, G3Polygon) {
  const Problem p = example("g3_polygon.textproto");
  EXPECT_EQ(p.geometry.name, "outer");
  const std::vector<Vec2> expected = {{-0.4, -0.5}, {0.4, -0.2}, {0.4, -0.7}, {1.5, -0.4},
                                      {0.9, 0.1},   {1.6, 0.8},  {0.5, 0.5},  {0.2, 1},
                                      {0.1, 0.4},   {-0.7, 0.7}};
  const Polygon& polygon = node<Polygon>(p.geometry);
  ASSERT_EQ(polygon.vertices.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(polygon.vertices[i], expected[i]) << i;
  EXPECT_TRUE(p.auto_corners);  // the 10 vertices
  expect_ci_size(p);
}

TEST(RequestConversionExamples, G4Ellipse) {
  const Problem p = example("g4_ellipse.textproto");
  EXPECT_EQ(p.geometry.name, "outer");
  const Ellipse& e = node<Ellipse>(p.geometry);
  EXPECT_EQ(e.center, (Vec2{0, 0}));
  EXPECT_EQ(e.semi_axis_x, 2.0);
  EXPECT_EQ(e.semi_axis_y, 1.0);
  expect_ci_size(p);
}

TEST(RequestConversionExamples, G5GradedHole) {
  const Problem p = example("g5_graded_hole.textproto");
  expect_square_with_hole(p.geometry);
  ASSERT_EQ(p.size.terms.size(), 1u);
  const DistanceSize& graded = std::get<DistanceSize>(p.size.terms[0]);
  EXPECT_EQ(graded.shape.path, "size.terms[0].distance.shape");
  const Circle& circle = node<Circle>(graded.shape);
  EXPECT_EQ(circle.center, (Vec2{0, 0}));
  EXPECT_EQ(circle.radius, 0.5);
  // h(p) = min(h_max, h_min + slope |d|) equals geometries.md's min(4 r - 1, 2) on the domain.
  for (double r = 0.5; r <= std::sqrt(2.0); r += 0.01) {
    const double d = r - circle.radius;
    const double h = std::min(graded.h_max, graded.h_min + graded.slope * std::fabs(d));
    EXPECT_NEAR(h, std::min(4 * r - 1, 2.0), 1e-12) << r;
  }
  expect_ci_size(p);
}

// The job's compiled problem keeps the survey that checked its node count, so that the worker's
// engine counts its multilevel levels without sampling the domain again; the survey over a pool
// gives the same estimate as on the caller's thread alone.
TEST(RequestConversionExamples, AJobKeepsItsSurvey) {
  const v1::MeshRequest request =
      read_request_file(std::string(MESHD_SOURCE_DIR) + "/examples/airfoil_channel.textproto");
  const JobSpec alone = to_job_spec(request);
  ThreadPool pool(3);
  const JobSpec shared = to_job_spec(request, {}, &pool);
  EXPECT_EQ(shared.estimated_nodes, alone.estimated_nodes);
  EXPECT_GT(alone.plane.inverse_size_integral, 0.0);
  EXPECT_EQ(shared.plane.inverse_size_integral, alone.plane.inverse_size_integral);
  EXPECT_EQ(estimate_node_count(alone.plane), alone.estimated_nodes);
  CompiledProblem unsurveyed = alone.plane;
  unsurveyed.inverse_size_integral = 0.0;
  EXPECT_EQ(estimate_node_count(unsurveyed), alone.estimated_nodes);
}

}  // namespace
}  // namespace meshd
