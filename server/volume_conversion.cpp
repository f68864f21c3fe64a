#include "server/volume_conversion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/common/error.h"
#include "core/distmesh3d/compiled_problem3d.h"
#include "core/distmesh3d/geometry_domain3d.h"
#include "core/distmesh3d/node_estimate3d.h"
#include "core/geometry3d/bounds3.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "server/field_checks.h"

namespace meshd {
namespace {

Vec3 to_vec3(const v1::Vec3& v, const std::string& field) {
  return {finite(v.x(), field + ".x"), finite(v.y(), field + ".y"), finite(v.z(), field + ".z")};
}

// ---------------------------------------------------------------------------------------------
// The Shape3 tree. One converter per tree: it counts the tree's nodes against the limit.

class Shape3Converter {
 public:
  Shape3Converter(const ConversionLimits& limits, std::string root)
      : limits_(limits), budget_(std::move(root), limits.max_tree_depth, limits.max_tree3_nodes) {}

  Shape3 convert(const v1::Shape3& shape) { return convert(shape, budget_.root(), 1, ""); }

 private:
  Shape3 convert(const v1::Shape3& in, const std::string& path, int depth,
                 const std::string& inherited_name) {
    budget_.enter(path, depth, in.name());

    Shape3 out;
    out.path = path;
    out.name = in.name().empty() ? inherited_name : in.name();
    const std::string& name = out.name;
    // The primitives' other ranges (a torus's radii, a cone's two radii) are checked by the
    // compiler, which names the same fields.
    switch (in.kind_case()) {
      case v1::Shape3::kSphere: {
        const std::string p = path + ".sphere";
        out.node = Sphere{to_vec3(in.sphere().center(), p + ".center"),
                          positive(in.sphere().radius(), p + ".radius")};
        break;
      }
      case v1::Shape3::kBox: {
        const std::string p = path + ".box";
        Cuboid c{to_vec3(in.box().min(), p + ".min"), to_vec3(in.box().max(), p + ".max")};
        if (!(c.max.x > c.min.x))
          throw_invalid(p + ".max.x", "must be > min.x = " + num(c.min.x) + got(c.max.x));
        if (!(c.max.y > c.min.y))
          throw_invalid(p + ".max.y", "must be > min.y = " + num(c.min.y) + got(c.max.y));
        if (!(c.max.z > c.min.z))
          throw_invalid(p + ".max.z", "must be > min.z = " + num(c.min.z) + got(c.max.z));
        out.node = c;
        break;
      }
      case v1::Shape3::kCylinder: {
        const std::string p = path + ".cylinder";
        const auto& c = in.cylinder();
        out.node =
            Cylinder{to_vec3(c.base_center(), p + ".base_center"),
                     positive(c.radius(), p + ".radius"), positive(c.height(), p + ".height")};
        break;
      }
      case v1::Shape3::kCone: {
        const std::string p = path + ".cone";
        const auto& c = in.cone();
        Frustum f;
        f.base_center = to_vec3(c.base_center(), p + ".base_center");
        f.bottom_radius = finite(c.bottom_radius(), p + ".bottom_radius");
        f.top_radius = finite(c.top_radius(), p + ".top_radius");
        f.height = positive(c.height(), p + ".height");
        out.node = f;
        break;
      }
      case v1::Shape3::kTorus: {
        const std::string p = path + ".torus";
        const auto& t = in.torus();
        out.node =
            Torus{to_vec3(t.center(), p + ".center"), finite(t.major_radius(), p + ".major_radius"),
                  positive(t.minor_radius(), p + ".minor_radius")};
        break;
      }
      case v1::Shape3::kHalfSpace: {
        const std::string p = path + ".half_space";
        const Vec3 normal = to_vec3(in.half_space().normal(), p + ".normal");
        if (normal == Vec3{}) {
          throw_invalid(p + ".normal",
                        "must be non-zero (got (0, 0, 0)); it need not be unit length");
        }
        out.node = HalfSpace{normal, finite(in.half_space().offset(), p + ".offset")};
        break;
      }
      case v1::Shape3::kExtrusion: {
        const std::string p = path + ".extrusion";
        const auto& e = in.extrusion();
        if (!e.has_profile()) throw_invalid(p + ".profile", "required: the plane shape to extrude");
        out.node = Extrusion{to_shape(e.profile(), limits_, p + ".profile"),
                             positive(e.height(), p + ".height")};
        break;
      }
      case v1::Shape3::kRevolution: {
        const std::string p = path + ".revolution";
        const auto& r = in.revolution();
        if (!r.has_profile()) throw_invalid(p + ".profile", "required: the plane shape to revolve");
        out.node = Revolution{to_shape(r.profile(), limits_, p + ".profile")};
        break;
      }
      case v1::Shape3::kPolyhedron:
        out.node = polyhedron(in.polyhedron(), path + ".polyhedron");
        break;
      case v1::Shape3::kUnion:
        out.node = csg(CsgOp::kUnion, in.union_().shapes(), path + ".union", depth, name);
        break;
      case v1::Shape3::kIntersection:
        out.node = csg(CsgOp::kIntersection, in.intersection().shapes(), path + ".intersection",
                       depth, name);
        break;
      case v1::Shape3::kDifference: {
        const std::string p = path + ".difference";
        const auto& d = in.difference();
        if (!d.has_base()) throw_invalid(p + ".base", "required: the solid to subtract from");
        Csg3 c{CsgOp::kDifference, {}};
        c.operands.reserve(1 + d.subtract_size());
        c.operands.push_back(convert(d.base(), p + ".base", depth + 1, name));
        for (int i = 0; i < d.subtract_size(); ++i) {
          c.operands.push_back(convert(d.subtract(i), at(p, "subtract", i), depth + 1, name));
        }
        out.node = std::move(c);
        break;
      }
      case v1::Shape3::kTranslate: {
        const std::string p = path + ".translate";
        const auto& t = in.translate();
        Similarity3 s;
        s.offset = to_vec3(t.offset(), p + ".offset");
        if (!t.has_shape()) throw_invalid(p + ".shape", "required: the solid to translate");
        out.node = Transformed3{s, {convert(t.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape3::kRotate: {
        // About c: p -> R(p - c) + c = R p + (c - R c).
        const std::string p = path + ".rotate";
        const auto& r = in.rotate();
        const double degrees = finite(r.angle_deg(), p + ".angle_deg");
        Similarity3 s;
        s.axis = to_vec3(r.axis(), p + ".axis");
        if (degrees != 0.0 && s.axis == Vec3{}) {
          throw_invalid(p + ".axis", "must be non-zero when angle_deg is not 0 (got (0, 0, 0))");
        }
        s.angle = degrees * (std::numbers::pi / 180.0);
        const Vec3 c = to_vec3(r.center(), p + ".center");
        s.offset = c - apply(s, c);
        if (!r.has_shape()) throw_invalid(p + ".shape", "required: the solid to rotate");
        out.node = Transformed3{s, {convert(r.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape3::kScale: {
        // About c: p -> f (p - c) + c = f p + (1 - f) c.
        const std::string p = path + ".scale";
        const auto& sc = in.scale();
        Similarity3 s;
        s.scale = positive(sc.factor(), p + ".factor");
        const Vec3 c = to_vec3(sc.center(), p + ".center");
        s.offset = (1.0 - s.scale) * c;
        if (!sc.has_shape()) throw_invalid(p + ".shape", "required: the solid to scale");
        out.node = Transformed3{s, {convert(sc.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape3::KIND_NOT_SET:
        throw_invalid(path,
                      "no shape kind set; set exactly one of sphere, box, cylinder, cone, torus, "
                      "half_space, extrusion, revolution, polyhedron, union, intersection, "
                      "difference, "
                      "translate, rotate, scale");
    }
    return out;
  }

  Csg3 csg(CsgOp op, const google::protobuf::RepeatedPtrField<v1::Shape3>& shapes,
           const std::string& path, int depth, const std::string& name) {
    if (shapes.empty()) throw_invalid(path + ".shapes", "needs at least 1 shape (got 0)");
    Csg3 c{op, {}};
    c.operands.reserve(shapes.size());
    for (int i = 0; i < shapes.size(); ++i) {
      c.operands.push_back(convert(shapes[i], at(path, "shapes", i), depth + 1, name));
    }
    return c;
  }

  // The arrays' shapes and the triangle budget; the surface's own rules (closed, manifold, no
  // zero area) are the compiler's, which names the same fields.
  Polyhedron polyhedron(const v1::Polyhedron& in, const std::string& p) {
    if (in.vertices_size() % 3 != 0) {
      throw_invalid(p + ".vertices", "must hold x, y, z triples (got " +
                                         std::to_string(in.vertices_size()) + " numbers)");
    }
    if (in.triangles_size() % 3 != 0) {
      throw_invalid(p + ".triangles", "must hold index triples (got " +
                                          std::to_string(in.triangles_size()) + " numbers)");
    }
    triangles_ += in.triangles_size() / 3;
    if (triangles_ > limits_.max_polyhedron_triangles) {
      throw Error(ErrorCode::kResourceExhausted, p + ".triangles",
                  "the request's polyhedra hold more than " +
                      std::to_string(limits_.max_polyhedron_triangles) + " triangles in all");
    }
    Polyhedron out;
    out.vertices.reserve(in.vertices_size() / 3);
    for (int i = 0; i < in.vertices_size(); i += 3) {
      const auto number = [&](int k) {
        return finite(in.vertices(i + k), at(p, "vertices", i + k));
      };
      out.vertices.push_back({number(0), number(1), number(2)});
    }
    const auto n = static_cast<uint32_t>(out.vertices.size());
    out.triangles.reserve(in.triangles_size() / 3);
    for (int i = 0; i < in.triangles_size(); i += 3) {
      std::array<int32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = in.triangles(i + k);
        if (v >= n) {
          throw_invalid(at(p, "triangles", i + k), "must be a vertex index in [0, " +
                                                       std::to_string(n) + ") (got " +
                                                       std::to_string(v) + ")");
        }
        t[k] = static_cast<int32_t>(v);
      }
      out.triangles.push_back(t);
    }
    return out;
  }

  const ConversionLimits& limits_;
  TreeBudget budget_;
  int64_t triangles_ = 0;
};

// ---------------------------------------------------------------------------------------------
// The size field.

SizeField3 size_field3(const v1::Volume& volume, const ConversionLimits& limits) {
  SizeField3 out;
  if (!volume.has_size()) return out;
  const auto& terms = volume.size().terms();
  if (terms.size() > limits.max_size_terms) {
    throw_invalid("volume.size.terms", "at most " + std::to_string(limits.max_size_terms) +
                                           " terms allowed (got " + std::to_string(terms.size()) +
                                           ")");
  }
  for (int i = 0; i < terms.size(); ++i) {
    const std::string p = at("volume.size", "terms", i);
    switch (terms[i].kind_case()) {
      case v1::SizeTerm3::kUniform:
        out.terms.emplace_back(
            UniformSize{positive(terms[i].uniform().value(), p + ".uniform.value")});
        break;
      case v1::SizeTerm3::kDistance: {
        const std::string q = p + ".distance";
        const auto& d = terms[i].distance();
        DistanceSize3 term;
        term.h_min = positive(d.h_min(), q + ".h_min");
        term.slope = d.slope();
        if (!(std::isfinite(term.slope) && term.slope >= 0)) {
          throw_invalid(q + ".slope", "must be finite and >= 0" + got(term.slope));
        }
        term.h_max = at_least_h_min(d.h_max(), term.h_min, q + ".h_max");
        if (!d.has_shape()) throw_invalid(q + ".shape", "required: the solid to measure from");
        term.shape = Shape3Converter(limits, q + ".shape").convert(d.shape());
        out.terms.emplace_back(std::in_place_type<DistanceSize3>, std::move(term));
        break;
      }
      case v1::SizeTerm3::KIND_NOT_SET:
        throw_invalid(p, "no size term kind set; set exactly one of uniform, distance");
    }
  }
  const SizeRange range = size_range3(out);
  if (range.high / range.low > limits.max_size_ratio) {
    throw_invalid("volume.size.terms", "the largest size over the smallest may be at most " +
                                           num(limits.max_size_ratio) + " (got " + num(range.low) +
                                           " to " + num(range.high) + ")");
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Parameters: each optional, with the 3D loop's defaults (params3d.h).

Params3 params3(const v1::MeshRequest& request) {
  Params3 out;
  out.seed = request.seed();
  if (!request.has_params()) return out;
  const auto& in = request.params();
  if (in.has_dptol()) out.dptol = in_range(in.dptol(), 0, true, 0.1, "params.dptol");
  if (in.has_ttol()) out.ttol = in_range(in.ttol(), 0, true, 1, "params.ttol");
  if (in.has_fscale()) out.fscale = in_range(in.fscale(), 1, false, 2, "params.fscale");
  if (in.has_deltat()) out.deltat = in_range(in.deltat(), 0, true, 0.5, "params.deltat");
  if (in.has_geps()) out.geps = in_range(in.geps(), 0, true, 0.1, "params.geps");
  if (in.has_density_control_interval()) {
    out.density_control_interval =
        in_range(in.density_control_interval(), 0, 1000, "params.density_control_interval");
  }
  if (in.has_max_iterations()) {
    out.max_iterations = in_range(in.max_iterations(), 1, 1'000'000, "params.max_iterations");
  }
  if (in.has_cleanup()) out.optimize_slivers = in.cleanup();
  if (in.has_momentum()) out.momentum = in_range(in.momentum(), 0, false, 0.9, "params.momentum");
  if (in.has_multilevel()) {
    throw_invalid("params.multilevel", "must stay unset for a volume: 3D has no multilevel start");
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// The node count, from the domain's volume weighted by the size field (node_estimate3d.h).

double check_node_count3(const CompiledProblem3& problem, const ConversionLimits& limits) {
  const Box3 bounds = domain_bounds3(*problem.geometry);
  const Program3View view = problem.geometry->view();
  const double low = problem.range.low;
  // The survey needs the sign, and the depth no deeper than the thickness check looks.
  const double band = problem.exact_band;
  const VolumeSurvey3 survey =
      survey_volume3d([view, band](Vec3 p) { return eval_sdf3(view, p, nullptr, band); },
                      size_callable3(problem.size, problem.uniform), bounds);
  const double volume = survey.weighted_volume;
  if (!(volume > 0)) {
    throw_invalid("volume.geometry",
                  "no point of a 32^3 grid over the domain's box lies inside: "
                  "the domain is empty or far thinner than its box");
  }
  const double h0 = problem.request_h0;
  const double nodes = node_count3d(volume, problem.h0);
  if (!(nodes >= 4)) {
    throw_invalid("h0", "h0 = " + num(h0) + " gives about " + approx(nodes) +
                            " nodes; at least 4 are needed: h0 must be at most about " +
                            approx(h0_for_node_count3d(volume, 4) / low));
  }
  if (nodes > static_cast<double>(limits.max_nodes)) {
    throw Error(
        ErrorCode::kResourceExhausted, "h0",
        "h0 = " + num(h0) + " gives about " + approx(nodes) + " nodes, more than the limit of " +
            std::to_string(limits.max_nodes) + ": h0 must be at least about " +
            approx(h0_for_node_count3d(volume, static_cast<double>(limits.max_nodes)) / low));
  }
  // The start spaces its nodes about h0 apart where h is finest: a domain much thinner than
  // that gets no tetrahedron (2D's check_thickness in 3D, from the grid's deepest point).
  const double thickness =
      std::min({2.0 * (survey.depth + survey.half_diagonal), bounds.max.x - bounds.min.x,
                bounds.max.y - bounds.min.y, bounds.max.z - bounds.min.z});
  if (thickness < 0.5 * h0 * low) {
    throw_invalid("h0", "h0 = " + num(h0) + ": the domain is at most about " + approx(thickness) +
                            " thick, and no tetrahedron of that size fits; h0 must be at most "
                            "about " +
                            approx(2.0 * thickness / low));
  }
  return nodes;
}

// The request's fields, each checked, as a Problem3 (its node count not yet checked).
Problem3 convert3(const v1::MeshRequest& request, const ConversionLimits& limits) {
  // The plane fields mean nothing to a volume: refuse them rather than ignore them.
  if (request.has_geometry())
    throw_invalid("geometry", "must be unset when volume is set (a request is 2D or 3D)");
  if (request.has_size()) throw_invalid("size", "must be unset for a volume: use volume.size");
  if (request.has_bbox()) throw_invalid("bbox", "must be unset for a volume");
  if (request.fixed_points_size() > 0) throw_invalid("fixed_points", "must be empty for a volume");
  if (request.has_auto_corners())
    throw_invalid("auto_corners", "must be unset for a volume: use volume.auto_features");

  const v1::Volume& volume = request.volume();
  Problem3 problem;
  if (!volume.has_geometry()) throw_invalid("volume.geometry", "required: the solid to mesh");
  problem.geometry = Shape3Converter(limits, "volume.geometry").convert(volume.geometry());
  problem.size = size_field3(volume, limits);
  problem.h0 = positive(request.h0(), "h0");
  problem.auto_features = volume.has_auto_features() ? volume.auto_features() : true;
  problem.params = params3(request);
  return problem;
}

}  // namespace

Problem3 to_problem3(const v1::MeshRequest& request, const ConversionLimits& limits,
                     double& estimated_nodes) {
  Problem3 problem = convert3(request, limits);
  estimated_nodes = check_node_count3(compile_problem3(problem), limits);
  return problem;
}

CompiledProblem3 to_compiled_problem3(const v1::MeshRequest& request,
                                      const ConversionLimits& limits, double& estimated_nodes) {
  CompiledProblem3 compiled = compile_problem3(convert3(request, limits));
  estimated_nodes = check_node_count3(compiled, limits);
  return compiled;
}

}  // namespace meshd
