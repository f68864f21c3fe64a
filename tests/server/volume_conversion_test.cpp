// Volume (3D) requests through the conversion layer: what a good one becomes, and every class of
// bad field named by its path with the allowed range.
#include "server/volume_conversion.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include "core/common/error.h"
#include "server/request_conversion.h"
#include "tests/server/conversion_expectations.h"

namespace meshd::testing {
namespace {

v1::MeshRequest parse(const std::string& text) {
  v1::MeshRequest request;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &request)) << text;
  return request;
}

void expect_error(const std::string& text, ErrorCode code, const std::string& field,
                  const std::string& message) {
  testing::expect_error(parse(text), code, field, message);
}

void expect_invalid(const std::string& text, const std::string& field, const std::string& message) {
  expect_error(text, ErrorCode::kInvalidArgument, field, message);
}

constexpr const char* kBall = "volume { geometry { sphere { radius: 1 } } } h0: 0.2 ";

TEST(VolumeConversion, ABallBecomesAProblem3WithItsDefaultsAndEstimate) {
  double estimated_nodes = 0;
  const Problem3 p = to_problem3(parse(std::string(kBall) + "seed: 7"), {}, estimated_nodes);
  ASSERT_TRUE(std::holds_alternative<Sphere>(p.geometry.node));
  EXPECT_EQ(std::get<Sphere>(p.geometry.node).radius, 1.0);
  EXPECT_EQ(p.geometry.path, "volume.geometry");
  EXPECT_EQ(p.h0, 0.2);
  EXPECT_TRUE(p.auto_features);
  EXPECT_EQ(p.params.seed, 7u);
  EXPECT_EQ(p.params.fscale, Params3{}.fscale);
  EXPECT_TRUE(p.params.optimize_slivers);
  // sqrt(2) (4/3 pi) / 0.2^3 = 740 nodes, up to the 64^3 grid's error.
  EXPECT_NEAR(estimated_nodes, 740.0, 30.0);

  // A job keeps the compilation its estimate was checked on, for its worker.
  const JobSpec spec = to_job_spec(parse(std::string(kBall) + "seed: 7"));
  ASSERT_TRUE(spec.volume.has_value());
  EXPECT_EQ(spec.estimated_nodes, estimated_nodes);
  ASSERT_NE(spec.volume->geometry, nullptr);
  EXPECT_EQ(spec.volume->geometry->primitives.size(), 1u);
  EXPECT_EQ(spec.volume->request_h0, 0.2);
  EXPECT_EQ(spec.volume->h0, 0.2);
  EXPECT_TRUE(spec.volume->uniform);
  EXPECT_EQ(spec.volume->params.seed, 7u);
}

TEST(VolumeConversion, ParametersSizeTermsAndNamesConvert) {
  const v1::MeshRequest request = parse(R"(
    volume {
      geometry { name: "part" difference {
        base { box { min { x: -1 y: -1 z: -1 } max { x: 1 y: 1 z: 1 } } }
        subtract { name: "hole" rotate { axis { x: 1 } angle_deg: 90 shape { cylinder {
          base_center { z: -2 } radius: 0.3 height: 4 } } } } } }
      size { terms { distance { shape { sphere { radius: 0.3 } } h_min: 0.5 slope: 2 h_max: 2 } }
             terms { uniform { value: 1.5 } } }
      auto_features: false
    }
    h0: 0.1
    params { dptol: 0.002 cleanup: false max_iterations: 50 })");
  double estimated_nodes = 0;
  const Problem3 p = to_problem3(request, {}, estimated_nodes);
  EXPECT_FALSE(p.auto_features);
  EXPECT_EQ(p.params.dptol, 0.002);
  EXPECT_FALSE(p.params.optimize_slivers);
  EXPECT_EQ(p.params.max_iterations, 50);
  ASSERT_EQ(p.size.terms.size(), 2u);
  EXPECT_EQ(size_range3(p.size).low, 0.5);
  const auto& csg = std::get<Csg3>(p.geometry.node);
  EXPECT_EQ(csg.operands[0].name, "part");  // inherited
  EXPECT_EQ(csg.operands[1].name, "hole");
  EXPECT_EQ(csg.operands[1].path, "volume.geometry.difference.subtract[0]");

  // Compiled, h0 is the finest edge: the request's h0 times the field's smallest value.
  const JobSpec spec = to_job_spec(request);
  ASSERT_TRUE(spec.volume.has_value());
  EXPECT_FALSE(spec.volume->uniform);
  EXPECT_EQ(spec.volume->range.low, 0.5);
  EXPECT_EQ(spec.volume->h0, 0.1 * 0.5);
  EXPECT_FALSE(spec.volume->auto_features);
}

TEST(VolumeConversion, BadFieldsAreNamedWithTheirRange) {
  expect_invalid("volume { geometry { sphere { radius: -1 } } } h0: 0.2",
                 "volume.geometry.sphere.radius", "must be finite and > 0 (got -1)");
  expect_invalid("volume { geometry { box { min { z: 1 } max { x: 1 y: 1 z: 1 } } } } h0: 0.2",
                 "volume.geometry.box.max.z", "must be > min.z = 1");
  expect_invalid(
      "volume { geometry { rotate { angle_deg: 30 shape { sphere { radius: 1 } } } } } h0: 0.2",
      "volume.geometry.rotate.axis", "must be non-zero");
  expect_invalid("volume { geometry { union { } } } h0: 0.2", "volume.geometry.union.shapes",
                 "needs at least 1 shape");
  expect_invalid("volume { geometry { } } h0: 0.2", "volume.geometry", "no shape kind set");
  expect_invalid(
      "volume { geometry { extrusion { profile { circle { radius: -1 } } height: 1 } } } h0: 0.2",
      "volume.geometry.extrusion.profile.circle.radius", "must be finite and > 0");
  expect_invalid(
      "volume { geometry { extrusion { profile { circle { radius: 1 } } height: 0 } } } h0: 0.2",
      "volume.geometry.extrusion.height", "must be finite and > 0");
  expect_invalid("volume { geometry { revolution { } } } h0: 0.2",
                 "volume.geometry.revolution.profile", "required");
  expect_invalid(
      "volume { geometry { revolution { profile { rectangle { max { x: 1 y: 1 } } } } } } h0: 0.2",
      "volume.geometry.revolution.profile", "touches the axis");
  expect_invalid("volume { geometry { sphere { radius: 1 } name: \"a b\" } } h0: 0.2",
                 "volume.geometry.name", "is not allowed");
  expect_invalid("volume { geometry { torus { major_radius: 0.5 minor_radius: 1 } } } h0: 0.2",
                 "volume.geometry.torus.major_radius", "");
  expect_invalid("volume { geometry { half_space { normal { z: 1 } } } } h0: 0.2",
                 "volume.geometry", "the domain is unbounded");
  expect_invalid(std::string(kBall) + "geometry { circle { radius: 1 } }", "geometry",
                 "must be unset when volume is set");
  expect_invalid(std::string(kBall) + "fixed_points { x: 0 }", "fixed_points", "must be empty");
  expect_invalid(std::string(kBall) + "params { multilevel: true }", "params.multilevel",
                 "must stay unset");
  expect_invalid(std::string(kBall) + "params { geps: 0.5 }", "params.geps", "must be in (0, 0.1]");
  expect_invalid(
      "volume { geometry { sphere { radius: 1 } } size { terms { distance { "
      "shape { sphere { radius: 1 } } h_min: 2 h_max: 1 } } } } h0: 0.2",
      "volume.size.terms[0].distance.h_max", "must be finite and >= h_min = 2");
  expect_invalid(
      "volume { geometry { sphere { radius: 1 } } size { terms { distance { "
      "h_min: 1 h_max: 2 } } } } h0: 0.2",
      "volume.size.terms[0].distance.shape", "required");
  expect_invalid("volume { geometry { sphere { radius: 1 } } } h0: 5", "h0",
                 "at least 4 are needed");
  expect_invalid(
      "volume { geometry { box { min { x: -10 y: -10 } max { x: 10 y: 10 z: 0.05 } } } } h0: 0.5",
      "h0", "no tetrahedron of that size fits");
  expect_error("volume { geometry { sphere { radius: 1 } } } h0: 0.001",
               ErrorCode::kResourceExhausted, "h0", "h0 must be at least about");
}

// The cube [-1, 1]^3 as a polyhedron of 12 triangles, as a request.
v1::MeshRequest cube_polyhedron_request() {
  v1::MeshRequest r = parse("h0: 0.25");
  v1::Polyhedron* p = r.mutable_volume()->mutable_geometry()->mutable_polyhedron();
  for (int k = 0; k < 8; ++k) {
    p->add_vertices(k & 1 ? 1 : -1);
    p->add_vertices(k & 2 ? 1 : -1);
    p->add_vertices(k & 4 ? 1 : -1);
  }
  for (uint32_t v : {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                     2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5})
    p->add_triangles(v);
  return r;
}

// A volume's snapshots: 2/5 of the plane limit, since each node carries about 2.5 times the
// bytes (three coordinates, some 5.5 tetrahedra).
TEST(VolumeConversion, SnapshotsOfVolumesHaveTheirOwnNodeLimit) {
  ConversionLimits limits;
  limits.max_snapshot_nodes = 1000;  // a volume's: 400; the ball at h0 0.2 has about 740 nodes
  EXPECT_EQ(volume_snapshot_nodes(limits), 400);
  EXPECT_EQ(to_job_spec(parse(std::string(kBall) + "options { snapshot_every: 5 }"))
                .options.snapshot_max_nodes,
            volume_snapshot_nodes(ConversionLimits{}));
  testing::expect_error(parse(std::string(kBall) + "options { snapshot_every: 5 }"),
                        ErrorCode::kResourceExhausted, "options.snapshot_every",
                        "at most 400 nodes", limits);
  testing::expect_error(parse(std::string(kBall) + "options { snapshot_max_nodes: 401 }"),
                        ErrorCode::kInvalidArgument, "options.snapshot_max_nodes", "[0, 400]",
                        limits);
  const JobSpec coarse = to_job_spec(parse("volume { geometry { sphere { radius: 1 } } } h0: 0.4 "
                                           "options { snapshot_every: 5 }"),
                                     limits);
  EXPECT_EQ(coarse.options.snapshot_every, 5);
  EXPECT_EQ(coarse.options.snapshot_max_nodes, 400);
}

TEST(VolumeConversion, PolyhedraAreCheckedAndCounted) {
  double estimated_nodes = 0;
  const Problem3 problem = to_problem3(cube_polyhedron_request(), {}, estimated_nodes);
  const auto& poly = std::get<Polyhedron>(problem.geometry.node);
  EXPECT_EQ(poly.vertices.size(), 8u);
  EXPECT_EQ(poly.triangles.size(), 12u);
  const std::string p = "volume.geometry.polyhedron";

  v1::MeshRequest r = cube_polyhedron_request();
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->add_vertices(1.0);
  testing::expect_invalid(r, p + ".vertices", "x, y, z triples (got 25 numbers)");
  r = cube_polyhedron_request();
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->set_vertices(4, NAN);
  testing::expect_invalid(r, p + ".vertices[4]", "must be finite");
  r = cube_polyhedron_request();
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->set_triangles(5, 8);
  testing::expect_invalid(r, p + ".triangles[5]", "vertex index in [0, 8) (got 8)");
  r = cube_polyhedron_request();
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->mutable_triangles()->Truncate(33);
  testing::expect_invalid(r, p + ".triangles", "must be closed");
  r = cube_polyhedron_request();
  // Vertex 7, the corner (1, 1, 1), pulled down through the bottom face.
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->set_vertices(21, 0.2);
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->set_vertices(22, 0.3);
  r.mutable_volume()->mutable_geometry()->mutable_polyhedron()->set_vertices(23, -3.0);
  testing::expect_invalid(r, p + ".triangles", "the surface intersects itself");
  ConversionLimits small;
  small.max_polyhedron_triangles = 11;
  testing::expect_error(cube_polyhedron_request(), ErrorCode::kResourceExhausted, p + ".triangles",
                        "more than 11 triangles", small);
}

TEST(VolumeConversion, ThePlaneEntryPointRefusesAVolume) {
  try {
    to_problem(parse(kBall));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "volume");
  }
}

}  // namespace
}  // namespace meshd::testing
