// Pathological requests (issue 6), one test per class, end to end through to_job_spec as the
// service converts them: each is refused with INVALID_ARGUMENT or RESOURCE_EXHAUSTED, on the
// field it concerns, with a message that states the limit or the allowed range. And a request
// that does not converge stops at max_iterations with a valid mesh that says so.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "client/request_file.h"
#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/mesh/validity.h"
#include "server/request_conversion.h"

namespace meshd {
namespace {

// ---------------------------------------------------------------------------------------------
// Helpers.

v1::MeshRequest parse(const std::string& text) { return parse_request_text(text, "test"); }

// `text` with every '@' replaced by `value`.
std::string fill(std::string text, const std::string& value) {
  for (size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at + 1)) {
    text.replace(at, 1, value);
  }
  return text;
}

// Checks that to_job_spec refuses `request` with `code`, on a field that starts with `field`
// (the message starts with that field too), with a message that contains each of `says`.
void expect_refused(const v1::MeshRequest& request, ErrorCode code, const std::string& field,
                    const std::vector<std::string>& says, const ConversionLimits& limits = {}) {
  try {
    to_job_spec(request, limits);
    ADD_FAILURE() << "accepted; expected " << error_code_name(code) << " on " << field;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_EQ(e.field().rfind(field, 0), 0u) << "field " << e.field() << ", expected " << field;
    EXPECT_EQ(std::string(e.what()).rfind(e.field() + ": ", 0), 0u) << e.what();
    for (const std::string& s : says) {
      EXPECT_NE(e.detail().find(s), std::string::npos)
          << "message: " << e.detail() << "\nexpected to contain: " << s;
    }
  }
}

void expect_invalid(const std::string& text, const std::string& field,
                    const std::vector<std::string>& says, const ConversionLimits& limits = {}) {
  SCOPED_TRACE(text);
  expect_refused(parse(text), ErrorCode::kInvalidArgument, field, says, limits);
}

const std::string kDisk = "geometry { circle { radius: 1 } } h0: 0.1 ";

// A polygon message from the given vertex list ("x y" pairs).
std::string polygon(const std::vector<std::pair<double, double>>& vertices) {
  std::string text = "polygon { ";
  for (const auto& [x, y] : vertices) {
    text += "vertices { x: " + std::to_string(x) + " y: " + std::to_string(y) + " } ";
  }
  return text + "}";
}

// ---------------------------------------------------------------------------------------------
// The tree: depth and size.

// `levels` nested translates around a unit circle: a tree of depth levels + 1.
v1::MeshRequest nested(int levels) {
  v1::MeshRequest request;
  request.set_h0(0.1);
  v1::Shape* shape = request.mutable_geometry();
  for (int i = 0; i < levels; ++i) shape = shape->mutable_translate()->mutable_shape();
  shape->mutable_circle()->set_radius(1);
  return request;
}

TEST(Pathological, TreeDepth) {
  EXPECT_NO_THROW(to_job_spec(nested(31)));  // depth 32, the default limit
  expect_refused(nested(32), ErrorCode::kInvalidArgument, "geometry.translate.shape",
                 {"deeper than the limit of 32 levels"});
  expect_refused(nested(1000), ErrorCode::kInvalidArgument, "geometry.translate.shape",
                 {"deeper than the limit of 32 levels"});
  // Unions nested in their first operand, under a lowered limit; and a size term's own tree.
  std::string unions = "circle { radius: 1 }";
  for (int i = 0; i < 5; ++i) unions = "union { shapes { " + unions + " } }";
  expect_invalid("geometry { " + unions + " } h0: 0.1", "geometry.union.shapes[0]",
                 {"deeper than the limit of 4 levels"}, ConversionLimits{.max_tree_depth = 4});
  expect_invalid(
      kDisk + "size { terms { distance { shape { " + unions + " } h_min: 1 h_max: 2 } } }",
      "size.terms[0].distance.shape.union.shapes[0]", {"deeper than the limit of 4 levels"},
      ConversionLimits{.max_tree_depth = 4});
}

TEST(Pathological, TreeNodeCount) {
  // A union of 100 circles is 101 nodes, one above the limit set here.
  const ConversionLimits limits{.max_tree_nodes = 100};
  v1::MeshRequest request = parse(kDisk);
  v1::Union* all = request.mutable_geometry()->mutable_union_();
  for (int i = 0; i < 100; ++i) all->add_shapes()->mutable_circle()->set_radius(1);
  expect_refused(request, ErrorCode::kInvalidArgument, "geometry",
                 {"more than the limit of 100 shape nodes"}, limits);
  // A size term's shape counts as a tree of its own.
  v1::MeshRequest sized = parse(kDisk + "size { terms { distance { h_min: 1 h_max: 2 } } }");
  v1::Union* shapes =
      sized.mutable_size()->mutable_terms(0)->mutable_distance()->mutable_shape()->mutable_union_();
  for (int i = 0; i < 100; ++i) shapes->add_shapes()->mutable_circle()->set_radius(1);
  expect_refused(sized, ErrorCode::kInvalidArgument, "size.terms[0].distance.shape",
                 {"more than the limit of 100 shape nodes"}, limits);
}

TEST(Pathological, DefaultLimitsTakeTenThousandShapesAndLongPolygons) {
  // Spatial indexes make both cheap to evaluate, so the defaults admit them.
  v1::MeshRequest request = parse("h0: 0.05");
  v1::Union* all = request.mutable_geometry()->mutable_union_();
  for (int i = 0; i < 10'000; ++i) {
    v1::Circle* c = all->add_shapes()->mutable_circle();
    c->mutable_center()->set_x(i % 100);
    c->mutable_center()->set_y(i / 100);
    c->set_radius(0.3);
  }
  EXPECT_NO_THROW(to_job_spec(request, ConversionLimits{}));
  v1::MeshRequest ring = parse("h0: 0.05");
  v1::Polygon* p = ring.mutable_geometry()->mutable_polygon();
  for (int i = 0; i < 200'000; ++i) {
    const double a = 2 * M_PI * i / 200'000;
    v1::Vec2* v = p->add_vertices();
    v->set_x(std::cos(a));
    v->set_y(std::sin(a));
  }
  EXPECT_NO_THROW(to_job_spec(ring, ConversionLimits{}));
}

// ---------------------------------------------------------------------------------------------
// Polygons.

TEST(Pathological, PolygonVertexCount) {
  v1::MeshRequest request = parse("h0: 0.1");
  v1::Polygon* p = request.mutable_geometry()->mutable_polygon();
  for (int i = 0; i < 1'001; ++i) {
    const double a = 2 * M_PI * i / 1'001;
    v1::Vec2* v = p->add_vertices();
    v->set_x(std::cos(a));
    v->set_y(std::sin(a));
  }
  expect_refused(request, ErrorCode::kInvalidArgument, "geometry.polygon.vertices",
                 {"at most 1000 vertices allowed (got 1001)"},
                 ConversionLimits{.max_polygon_vertices = 1'000});
  expect_invalid("geometry { " + polygon({{0, 0}, {1, 0}}) + " } h0: 0.1",
                 "geometry.polygon.vertices", {"at least 3 vertices (got 2)"});
}

TEST(Pathological, CoincidentOrSelfIntersectingPolygons) {
  struct Case {
    std::vector<std::pair<double, double>> vertices;
    const char* what;
  };
  const Case cases[] = {
      {{{0, 0}, {2, 0}, {2, 2}, {0, 0}, {0, 2}}, "vertices 0 and 3 are the same point (0, 0)"},
      {{{0, 0}, {1, 0}, {1, 1}, {0, 0}}, "do not repeat the first vertex at the end"},
      {{{0, 0}, {1, 1}, {1, 0}, {0, 1}}, "edges 0 and 2 cross near (0.5, 0.5)"},
      {{{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}, "touch at (2, 0)"},
      {{{0, 0}, {2, 0}, {1, 0}, {1, 1}}, "edges 0 and 1 overlap"},
  };
  for (const Case& c : cases) {
    // Inside a difference, as a hole: the path says which polygon.
    expect_invalid("geometry { difference { base { circle { radius: 9 } } subtract { " +
                       polygon(c.vertices) + " } } } h0: 0.5",
                   "geometry.difference.subtract[0].polygon.vertices",
                   {c.what, "a polygon must be simple"});
  }
  // Two coincident polygons, one subtracted from the other, leave nothing.
  const std::string square = polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  expect_invalid(
      "geometry { difference { base { " + square + " } subtract { " + square + " } } } h0: 0.1",
      "geometry", {"the domain is empty"});
}

// ---------------------------------------------------------------------------------------------
// Domains without area.

TEST(Pathological, ZeroAreaDomains) {
  expect_invalid("geometry { rectangle { min { x: 1 } max { x: 1 y: 1 } } } h0: 0.1",
                 "geometry.rectangle.max.x", {"must be > min.x = 1 (got 1)"});
  expect_invalid("geometry { circle { radius: 0 } } h0: 0.1", "geometry.circle.radius",
                 {"must be finite and > 0 (got 0)"});
  expect_invalid("geometry { ellipse { semi_axis_x: 1 semi_axis_y: 0 } } h0: 0.1",
                 "geometry.ellipse.semi_axis_y", {"must be finite and > 0 (got 0)"});
  expect_invalid("geometry { scale { factor: 0 shape { circle { radius: 1 } } } } h0: 0.1",
                 "geometry.scale.factor", {"must be finite and > 0 (got 0)"});
  expect_invalid("geometry { " + polygon({{0, 0}, {1, 1}, {3, 3}}) + " } h0: 0.1",
                 "geometry.polygon.vertices", {"zero area", "a polygon must be simple"});
  // Two squares that share an edge and nothing else: their intersection is a segment.
  expect_invalid(
      "geometry { intersection { shapes { rectangle { min { x: 0 y: 0 } max { x: 1 y: 1 } } } "
      "shapes { rectangle { min { x: 1 y: 0 } max { x: 2 y: 1 } } } } } h0: 0.1",
      "geometry", {"[1, 1] x [0, 1]", "width and height must be finite and > 0"});
  // A bbox that only touches the disk.
  expect_invalid(kDisk + "bbox { min { x: 1 y: -1 } max { x: 2 y: 1 } }", "geometry",
                 {"width and height must be finite and > 0"});
  // A disk minus itself.
  expect_invalid(
      "geometry { difference { base { circle { radius: 1 } } subtract { circle { "
      "radius: 1 } } } } h0: 0.1",
      "geometry", {"the domain is empty"});
}

TEST(Pathological, EmptyIntersections) {
  expect_invalid(
      "geometry { intersection { shapes { circle { center { x: -2 } radius: 1 } } "
      "shapes { circle { center { x: 2 } radius: 1 } } } } h0: 0.1",
      "geometry", {"the domain is empty"});
  // The half-plane x <= -1 misses the unit square; the boxes alone cannot tell.
  expect_invalid(
      "geometry { intersection { shapes { rectangle { max { x: 1 y: 1 } } } "
      "shapes { half_plane { normal { x: 1 } offset: -1 } } } } h0: 0.1",
      "geometry", {"the domain is empty"});
  expect_invalid(kDisk + "bbox { min { x: 5 y: 5 } max { x: 6 y: 6 } }", "bbox",
                 {"does not overlap the geometry"});
  expect_invalid(
      "geometry { difference { base { circle { radius: 1 } } subtract { circle { "
      "radius: 2 } } } } h0: 0.1",
      "geometry", {"the domain is empty"});
}

// The first points come from a grid over the domain's box: a domain that fills little of it
// would cost far more than its node estimate.
TEST(Pathological, DomainThatFillsLittleOfItsBox) {
  // Two unit disks 20,000 apart: about 73,000 nodes, but a grid of 4.6e8 points.
  expect_refused(parse("geometry { union { shapes { circle { center { x: -10000 } radius: 1 } } "
                       "shapes { circle { center { x: 10000 } radius: 1 } } } } h0: 0.01"),
                 ErrorCode::kResourceExhausted, "h0",
                 {"more than the limit of 320000000 (64 per node of the node limit)",
                  "the domain fills little of its box: h0 must be at least about 0.01"});
  // A 1e4 x 1e-4 strip: about 2,900 nodes by its area, a grid row of 500,000 on its boundary.
  ConversionLimits limits;
  limits.max_nodes = 3000;
  expect_refused(parse("geometry { rectangle { max { x: 10000 y: 0.0001 } } } h0: 0.02"),
                 ErrorCode::kResourceExhausted, "h0",
                 {"more than the limit of 192000", "[0, 10000] x [0, 1e-04]",
                  "h0 must be at least about 0.078"},
                 limits);
}

// ---------------------------------------------------------------------------------------------
// h0 at its extremes: too fine is RESOURCE_EXHAUSTED, too coarse (fewer than 3 nodes) invalid;
// the message says which h0 would do, even where the estimate over- or underflows.

TEST(Pathological, H0TooSmall) {
  for (const char* h0 : {"1e-4", "1e-100", "1e-200", "5e-324"}) {
    SCOPED_TRACE(h0);
    expect_refused(parse(std::string("geometry { circle { radius: 1 } } h0: ") + h0),
                   ErrorCode::kResourceExhausted, "h0",
                   {"nodes, more than the limit of 5000000: h0 must be at least about 0.00085"});
  }
  expect_refused(parse("geometry { circle { radius: 1 } } h0: 0.04"), ErrorCode::kResourceExhausted,
                 "h0", {"more than the limit of 1000: h0 must be at least about 0.06"},
                 ConversionLimits{.max_nodes = 1000});
}

TEST(Pathological, H0TooLarge) {
  for (const char* h0 : {"10", "1e100", "1e300", "1.7e308"}) {
    SCOPED_TRACE(h0);
    expect_invalid(std::string("geometry { circle { radius: 1 } } h0: ") + h0, "h0",
                   {"at least 3 are needed: h0 must be at most about 1.1"});
  }
}

// ---------------------------------------------------------------------------------------------
// NaN and infinities in every numeric field of the request.

TEST(Pathological, NonFiniteNumbersEverywhere) {
  const std::string circle = "shape { circle { radius: 1 } } ";
  const std::string distance = "size { terms { distance { " + circle;
  struct Case {
    std::string text;  // '@' stands for the value
    std::string field;
  };
  const std::vector<Case> cases = {
      {"geometry { circle { center { x: @ } radius: 1 } } h0: 0.1", "geometry.circle.center.x"},
      {"geometry { circle { center { y: @ } radius: 1 } } h0: 0.1", "geometry.circle.center.y"},
      {"geometry { circle { radius: @ } } h0: 0.1", "geometry.circle.radius"},
      {"geometry { rectangle { min { x: @ } max { x: 1 y: 1 } } } h0: 0.1",
       "geometry.rectangle.min.x"},
      {"geometry { rectangle { min { y: @ } max { x: 1 y: 1 } } } h0: 0.1",
       "geometry.rectangle.min.y"},
      {"geometry { rectangle { max { x: @ y: 1 } } } h0: 0.1", "geometry.rectangle.max.x"},
      {"geometry { rectangle { max { x: 1 y: @ } } } h0: 0.1", "geometry.rectangle.max.y"},
      {"geometry { polygon { vertices { } vertices { x: @ } vertices { y: 1 } } } h0: 0.1",
       "geometry.polygon.vertices[1].x"},
      {"geometry { polygon { vertices { } vertices { x: 1 } vertices { y: @ } } } h0: 0.1",
       "geometry.polygon.vertices[2].y"},
      {"geometry { ellipse { center { x: @ } semi_axis_x: 1 semi_axis_y: 1 } } h0: 0.1",
       "geometry.ellipse.center.x"},
      {"geometry { ellipse { center { y: @ } semi_axis_x: 1 semi_axis_y: 1 } } h0: 0.1",
       "geometry.ellipse.center.y"},
      {"geometry { ellipse { semi_axis_x: @ semi_axis_y: 1 } } h0: 0.1",
       "geometry.ellipse.semi_axis_x"},
      {"geometry { ellipse { semi_axis_x: 1 semi_axis_y: @ } } h0: 0.1",
       "geometry.ellipse.semi_axis_y"},
      {"geometry { half_plane { normal { x: @ } } } h0: 0.1", "geometry.half_plane.normal.x"},
      {"geometry { half_plane { normal { x: 1 y: @ } } } h0: 0.1", "geometry.half_plane.normal.y"},
      {"geometry { half_plane { normal { x: 1 } offset: @ } } h0: 0.1",
       "geometry.half_plane.offset"},
      {"geometry { translate { offset { x: @ } " + circle + "} } h0: 0.1",
       "geometry.translate.offset.x"},
      {"geometry { translate { offset { y: @ } " + circle + "} } h0: 0.1",
       "geometry.translate.offset.y"},
      {"geometry { rotate { angle_deg: @ " + circle + "} } h0: 0.1", "geometry.rotate.angle_deg"},
      {"geometry { rotate { center { x: @ } " + circle + "} } h0: 0.1", "geometry.rotate.center.x"},
      {"geometry { rotate { center { y: @ } " + circle + "} } h0: 0.1", "geometry.rotate.center.y"},
      {"geometry { scale { factor: @ " + circle + "} } h0: 0.1", "geometry.scale.factor"},
      {"geometry { scale { factor: 2 center { x: @ } " + circle + "} } h0: 0.1",
       "geometry.scale.center.x"},
      {"geometry { scale { factor: 2 center { y: @ } " + circle + "} } h0: 0.1",
       "geometry.scale.center.y"},
      {"geometry { circle { radius: 1 } } h0: @", "h0"},
      {kDisk + "size { terms { uniform { value: @ } } }", "size.terms[0].uniform.value"},
      {kDisk + distance + "h_min: @ h_max: 2 } } }", "size.terms[0].distance.h_min"},
      {kDisk + distance + "h_min: 1 slope: @ h_max: 2 } } }", "size.terms[0].distance.slope"},
      {kDisk + distance + "h_min: 1 h_max: @ } } }", "size.terms[0].distance.h_max"},
      {kDisk + "size { terms { distance { shape { circle { center { x: @ } radius: 1 } } h_min: 1 "
               "h_max: 2 } } }",
       "size.terms[0].distance.shape.circle.center.x"},
      {kDisk + "bbox { min { x: @ } max { x: 1 y: 1 } }", "bbox.min.x"},
      {kDisk + "bbox { min { y: @ } max { x: 1 y: 1 } }", "bbox.min.y"},
      {kDisk + "bbox { max { x: @ y: 1 } }", "bbox.max.x"},
      {kDisk + "bbox { max { x: 1 y: @ } }", "bbox.max.y"},
      {kDisk + "fixed_points { x: @ }", "fixed_points[0].x"},
      {kDisk + "fixed_points { } fixed_points { y: @ }", "fixed_points[1].y"},
      {kDisk + "params { dptol: @ }", "params.dptol"},
      {kDisk + "params { ttol: @ }", "params.ttol"},
      {kDisk + "params { fscale: @ }", "params.fscale"},
      {kDisk + "params { deltat: @ }", "params.deltat"},
      {kDisk + "params { geps: @ }", "params.geps"},
      {kDisk + "params { momentum: @ }", "params.momentum"},
      {kDisk + "options { timeout_s: @ }", "options.timeout_s"},
  };
  for (const Case& c : cases) {
    for (const std::string value : {"nan", "inf", "-inf"}) {
      const std::string text = fill(c.text, value);
      SCOPED_TRACE(text);
      // Each message states the range ("must be finite", "must be in [0, 86400]") and the value.
      expect_refused(parse(text), ErrorCode::kInvalidArgument, c.field,
                     {"must be", "(got " + value + ")"});
    }
  }
}

// Finite numbers whose combination is not: transforms fold into the primitives, and the
// evaluators square coordinates.
TEST(Pathological, NumbersThatOverflowTogether) {
  const std::string rule = "must be finite, within +-1e150, and lengths > 0";
  expect_invalid(
      "geometry { scale { factor: 1e300 shape { scale { factor: 1e300 shape { circle { radius: 1 "
      "} } } } } } h0: 0.1",
      "geometry.scale.shape.scale.shape", {"after the transforms above it, is", rule});
  expect_invalid(
      "geometry { scale { factor: 1e-300 shape { scale { factor: 1e-300 shape { circle { radius: "
      "1 } } } } } } h0: 0.1",
      "geometry.scale.shape.scale.shape", {"its size, after the transforms above it, is 0", rule});
  expect_invalid(
      "geometry { translate { offset { x: 1e308 } shape { translate { offset { x: 1e308 } shape { "
      "polygon { vertices { } vertices { x: 1 } vertices { y: 1 } } } } } } } h0: 0.1",
      "geometry.translate.shape.translate.shape", {"is inf", rule});
  expect_invalid("geometry { circle { radius: 1e200 } } h0: 1e199", "geometry",
                 {"is 1e+200", rule});
  expect_invalid(kDisk +
                     "size { terms { distance { shape { rectangle { min { x: -1e160 } max { "
                     "x: 1 y: 1 } } } h_min: 1 h_max: 2 } } }",
                 "size.terms[0].distance.shape", {"is -5e+159", rule});
  // A tiny normal is still a direction.
  EXPECT_NO_THROW(
      to_job_spec(parse("geometry { half_plane { normal { x: 1e-300 } } } h0: 0.1 "
                        "bbox { min { x: -1 y: -1 } max { x: 1 y: 1 } }")));
}

// A domain far from the origin compared with h0: the loop's finite-difference step rounds away.
TEST(Pathological, CoordinatesTooFarForH0) {
  expect_invalid(
      "geometry { circle { center { x: 2e7 y: 2e7 } radius: 1 } } h0: 0.1", "h0",
      {"too fine for a domain 20000001 from the origin",
       "must be at least 1e-07 times the largest coordinate", "h0 must be at least about 2"});
  // The finest edge counts: a size field finer than 1 makes it finer than h0.
  expect_invalid(
      "geometry { circle { center { x: 1e6 } radius: 1 } } h0: 0.5 size { terms { "
      "uniform { value: 0.1 } } }",
      "h0", {"h0 times the size field's smallest value = 0.05"});
  EXPECT_NO_THROW(
      to_job_spec(parse("geometry { circle { center { x: 9e5 y: -9e5 } radius: 1 } } h0: 0.1")));
}

// ---------------------------------------------------------------------------------------------
// The size field: values that vanish, and ratios that explode.

TEST(Pathological, SizeFieldVanishes) {
  const std::string distance =
      kDisk + "size { terms { distance { shape { circle { radius: 0.5 } } ";
  expect_invalid(kDisk + "size { terms { uniform { value: 0 } } }", "size.terms[0].uniform.value",
                 {"must be finite and > 0 (got 0)"});
  expect_invalid(kDisk + "size { terms { uniform { value: -1 } } }", "size.terms[0].uniform.value",
                 {"must be finite and > 0 (got -1)"});
  expect_invalid(distance + "h_min: 0 h_max: 1 } } }", "size.terms[0].distance.h_min",
                 {"must be finite and > 0 (got 0)"});
  expect_invalid(distance + "h_min: -1 h_max: 1 } } }", "size.terms[0].distance.h_min",
                 {"must be finite and > 0 (got -1)"});
  // A negative slope would reach 0 at some distance.
  expect_invalid(distance + "h_min: 1 slope: -0.5 h_max: 1 } } }", "size.terms[0].distance.slope",
                 {"must be finite and >= 0 (got -0.5)"});
  expect_invalid(distance + "h_min: 1 slope: 1 h_max: 0 } } }", "size.terms[0].distance.h_max",
                 {"must be finite and >= h_min = 1 (got 0)"});
  // A tiny h_min next to an ordinary h_max is the ratio limit.
  expect_invalid(distance + "h_min: 1e-300 slope: 1 h_max: 1 } } }", "size",
                 {"at most 1000 allowed"});
  // Uniformly tiny: as fine as a tiny h0, and said the same way, even past the double range.
  expect_refused(parse(kDisk + "size { terms { uniform { value: 1e-6 } } }"),
                 ErrorCode::kResourceExhausted, "h0",
                 {"more than the limit of 5000000: h0 must be at least about 85"});
  expect_refused(parse(kDisk + "size { terms { uniform { value: 1e-300 } } }"),
                 ErrorCode::kResourceExhausted, "h0",
                 {"more than 1e308 nodes, more than the limit of 5000000: h0 must be at least "
                  "about 8.5"});
}

TEST(Pathological, SizeFieldExplodes) {
  const std::string distance =
      kDisk + "size { terms { distance { shape { circle { radius: 0.5 } } ";
  expect_invalid(distance + "h_min: 1 slope: 1 h_max: 2000 } } }", "size",
                 {"factor up to 2000", "at most 1000 allowed"});
  ConversionLimits limits;
  limits.max_size_ratio = 10;
  expect_invalid(distance + "h_min: 1 slope: 100 h_max: 11 } } }", "size", {"at most 10 allowed"},
                 limits);
  // A steep slope is fine while h_max bounds it.
  EXPECT_NO_THROW(to_job_spec(parse(distance + "h_min: 1 slope: 1e300 h_max: 2 } } }")));
  // Uniformly huge: as coarse as a huge h0.
  expect_invalid(kDisk + "size { terms { uniform { value: 1e300 } } }", "h0",
                 {"at least 3 are needed: h0 must be at most about 1.1e-300"});
  v1::MeshRequest many = parse(kDisk);
  for (int i = 0; i < 101; ++i) many.mutable_size()->add_terms()->mutable_uniform()->set_value(1);
  expect_refused(many, ErrorCode::kInvalidArgument, "size.terms",
                 {"at most 100 terms allowed (got 101)"});
}

// ---------------------------------------------------------------------------------------------
// A request that does not converge: it stops at max_iterations, and the result says so.

TEST(Pathological, NotConvergedStopsAtMaxIterations) {
  const JobSpec spec =
      to_job_spec(parse("geometry { rectangle { min { x: -1 y: -1 } max { x: 1 y: 1 } } } "
                        "h0: 0.1 params { max_iterations: 3 }"));
  ASSERT_EQ(spec.plane.params.max_iterations, 3);
  const CompiledProblem& compiled = spec.plane;
  ThreadPool pool(1);
  CpuEngine engine(pool);
  const MeshResult result = generate_mesh(compiled, engine, nullptr, nullptr);
  EXPECT_FALSE(result.stats.converged);
  EXPECT_EQ(result.stats.iterations, 3);
  EXPECT_EQ(result.stats.cleanup_iterations, 0);  // the clean-up counts against the cap too
  const ValidityReport report = check_validity(result.mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems.front());
  EXPECT_GT(result.mesh.triangles.size(), 100u);
}

}  // namespace
}  // namespace meshd
