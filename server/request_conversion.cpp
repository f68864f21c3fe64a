#include "server/request_conversion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/polygon_checks.h"
#include "core/mesh/mesh.h"
#include "server/distance_grid_conversion.h"
#include "server/field_checks.h"
#include "server/size_grid_conversion.h"
#include "server/volume_conversion.h"

namespace meshd {
namespace {

// ---------------------------------------------------------------------------------------------
// Messages: estimates (field_checks.h has the value as the user wrote it).

// A box given by its corners: max above min in both coordinates.
void check_min_below_max(Vec2 min, Vec2 max, const std::string& field) {
  if (!(max.x > min.x))
    throw_invalid(field + ".max.x", "must be > min.x = " + num(min.x) + got(max.x));
  if (!(max.y > min.y))
    throw_invalid(field + ".max.y", "must be > min.y = " + num(min.y) + got(max.y));
}

// ---------------------------------------------------------------------------------------------
// The Shape tree. One converter per tree: it counts the tree's nodes against the limit.

class ShapeConverter {
 public:
  ShapeConverter(const ConversionLimits& limits, std::string root)
      : limits_(limits), budget_(std::move(root), limits.max_tree_depth, limits.max_tree_nodes) {}

  Shape convert(const v1::Shape& shape) { return convert(shape, budget_.root(), 1, ""); }

 private:
  Shape convert(const v1::Shape& in, const std::string& path, int depth,
                const std::string& inherited_name) {
    budget_.enter(path, depth, in.name());

    Shape out;
    out.path = path;
    out.name = in.name().empty() ? inherited_name : in.name();
    const std::string& name = out.name;
    switch (in.kind_case()) {
      case v1::Shape::kCircle: {
        const std::string p = path + ".circle";
        out.node = Circle{to_vec2(in.circle().center(), p + ".center"),
                          positive(in.circle().radius(), p + ".radius")};
        break;
      }
      case v1::Shape::kRectangle: {
        const std::string p = path + ".rectangle";
        Rectangle r{to_vec2(in.rectangle().min(), p + ".min"),
                    to_vec2(in.rectangle().max(), p + ".max")};
        check_min_below_max(r.min, r.max, p);
        out.node = r;
        break;
      }
      case v1::Shape::kPolygon:
        out.node = polygon(in.polygon(), path + ".polygon");
        break;
      case v1::Shape::kEllipse: {
        const std::string p = path + ".ellipse";
        out.node = Ellipse{to_vec2(in.ellipse().center(), p + ".center"),
                           positive(in.ellipse().semi_axis_x(), p + ".semi_axis_x"),
                           positive(in.ellipse().semi_axis_y(), p + ".semi_axis_y")};
        break;
      }
      case v1::Shape::kHalfPlane: {
        const std::string p = path + ".half_plane";
        const Vec2 normal = to_vec2(in.half_plane().normal(), p + ".normal");
        if (normal.x == 0 && normal.y == 0) {
          throw_invalid(p + ".normal", "must be non-zero (got (0, 0)); it need not be unit length");
        }
        out.node = HalfPlane{normal, finite(in.half_plane().offset(), p + ".offset")};
        break;
      }
      case v1::Shape::kDistanceGrid:
        out.node = to_distance_grid(in.distance_grid(), path + ".distance_grid",
                                    limits_.max_grid_samples, grid_samples_);
        break;
      case v1::Shape::kUnion:
        out.node = csg(CsgOp::kUnion, in.union_().shapes(), path + ".union", depth, name);
        break;
      case v1::Shape::kIntersection:
        out.node = csg(CsgOp::kIntersection, in.intersection().shapes(), path + ".intersection",
                       depth, name);
        break;
      case v1::Shape::kDifference: {
        const std::string p = path + ".difference";
        const auto& d = in.difference();
        if (!d.has_base()) throw_invalid(p + ".base", "required: the shape to subtract from");
        Csg c{CsgOp::kDifference, {}};
        c.operands.reserve(1 + d.subtract_size());
        c.operands.push_back(convert(d.base(), p + ".base", depth + 1, name));
        for (int i = 0; i < d.subtract_size(); ++i) {
          c.operands.push_back(convert(d.subtract(i), at(p, "subtract", i), depth + 1, name));
        }
        out.node = std::move(c);
        break;
      }
      case v1::Shape::kTranslate: {
        const std::string p = path + ".translate";
        const auto& t = in.translate();
        Similarity s;
        s.offset = to_vec2(t.offset(), p + ".offset");
        if (!t.has_shape()) throw_invalid(p + ".shape", "required: the shape to translate");
        out.node = Transformed{s, {convert(t.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape::kRotate: {
        // About c: p -> R(p - c) + c = R p + (c - R c).
        const std::string p = path + ".rotate";
        const auto& r = in.rotate();
        const double degrees = finite(r.angle_deg(), p + ".angle_deg");
        const Vec2 c = to_vec2(r.center(), p + ".center");
        Similarity s;
        s.angle = degrees * (std::numbers::pi / 180.0);
        s.offset = c - apply(s, c);
        if (!r.has_shape()) throw_invalid(p + ".shape", "required: the shape to rotate");
        out.node = Transformed{s, {convert(r.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape::kScale: {
        // About c: p -> f (p - c) + c = f p + (1 - f) c.
        const std::string p = path + ".scale";
        const auto& sc = in.scale();
        Similarity s;
        s.scale = positive(sc.factor(), p + ".factor");
        const Vec2 c = to_vec2(sc.center(), p + ".center");
        s.offset = (1.0 - s.scale) * c;
        if (!sc.has_shape()) throw_invalid(p + ".shape", "required: the shape to scale");
        out.node = Transformed{s, {convert(sc.shape(), p + ".shape", depth + 1, name)}};
        break;
      }
      case v1::Shape::KIND_NOT_SET:
        throw_invalid(path,
                      "no shape kind set; set exactly one of circle, rectangle, polygon, ellipse, "
                      "half_plane, distance_grid, union, intersection, difference, translate, "
                      "rotate, scale");
    }
    return out;
  }

  Csg csg(CsgOp op, const google::protobuf::RepeatedPtrField<v1::Shape>& shapes,
          const std::string& path, int depth, const std::string& name) {
    if (shapes.empty()) throw_invalid(path + ".shapes", "needs at least 1 shape (got 0)");
    Csg c{op, {}};
    c.operands.reserve(shapes.size());
    for (int i = 0; i < shapes.size(); ++i) {
      c.operands.push_back(convert(shapes[i], at(path, "shapes", i), depth + 1, name));
    }
    return c;
  }

  Polygon polygon(const v1::Polygon& in, const std::string& path) {
    if (in.vertices_size() > limits_.max_polygon_vertices) {
      throw_invalid(path + ".vertices", "at most " + std::to_string(limits_.max_polygon_vertices) +
                                            " vertices allowed (got " +
                                            std::to_string(in.vertices_size()) + ")");
    }
    Polygon out;
    out.vertices.reserve(in.vertices_size());
    for (int i = 0; i < in.vertices_size(); ++i) {
      out.vertices.push_back(to_vec2(in.vertices(i), at(path, "vertices", i)));
    }
    check_simple_polygon(out.vertices, path);
    return out;
  }

  const ConversionLimits& limits_;
  TreeBudget budget_;
  int64_t grid_samples_ = 0;
};

}  // namespace

Shape to_shape(const v1::Shape& shape, const ConversionLimits& limits, const std::string& path) {
  return ShapeConverter(limits, path).convert(shape);
}

namespace {

// ---------------------------------------------------------------------------------------------
// The size field.

// The steepest gradation: edges may grow by 10 length units per length unit.
constexpr double kMaxGradation = 10;
// The most edges a feature-size term may ask for across a narrow part.
constexpr double kMaxFeatureElements = 1000;

SizeFieldSpec size_field(const v1::MeshRequest& request, const ConversionLimits& limits) {
  SizeFieldSpec out;
  if (!request.has_size()) return out;
  const auto& terms = request.size().terms();
  if (terms.size() > limits.max_size_terms) {
    throw_invalid("size.terms", "at most " + std::to_string(limits.max_size_terms) +
                                    " terms allowed (got " + std::to_string(terms.size()) + ")");
  }

  // h = min over terms, so max h <= min over terms of each term's largest value, and
  // min h >= min over terms of each term's smallest value.
  double largest = std::numeric_limits<double>::infinity(), smallest = largest;
  int largest_term = -1, smallest_term = -1;
  int64_t grid_values = 0;
  for (int i = 0; i < terms.size(); ++i) {
    const std::string p = at("size", "terms", i);
    double low = 0.0, high = 0.0;
    switch (terms[i].kind_case()) {
      case v1::SizeTerm::kUniform: {
        const double v = positive(terms[i].uniform().value(), p + ".uniform.value");
        out.terms.emplace_back(UniformSize{v});  // braces: clang 14 has no aggregate (v)
        low = high = v;
        break;
      }
      case v1::SizeTerm::kDistance: {
        const std::string q = p + ".distance";
        const auto& d = terms[i].distance();
        DistanceSize term;
        term.h_min = positive(d.h_min(), q + ".h_min");
        term.slope = d.slope();
        if (!(std::isfinite(term.slope) && term.slope >= 0)) {
          throw_invalid(q + ".slope", "must be finite and >= 0" + got(term.slope));
        }
        term.h_max = at_least_h_min(d.h_max(), term.h_min, q + ".h_max");
        if (!d.has_shape()) throw_invalid(q + ".shape", "required: the shape to measure from");
        term.shape = ShapeConverter(limits, q + ".shape").convert(d.shape());
        low = term.h_min;
        high = term.h_max;
        out.terms.emplace_back(std::in_place_type<DistanceSize>, std::move(term));
        break;
      }
      case v1::SizeTerm::kGrid: {
        GridSize grid =
            to_grid_size(terms[i].grid(), p + ".grid", limits.max_size_grid_values, grid_values);
        const SizeRange range = size_term_range(grid);
        low = range.low;
        high = range.high;
        out.terms.emplace_back(std::in_place_type<GridSize>, std::move(grid));
        break;
      }
      case v1::SizeTerm::kFeature: {
        const std::string q = p + ".feature";
        const auto& f = terms[i].feature();
        FeatureSize term;
        term.elements = f.elements();
        if (!(term.elements >= 1 && term.elements <= kMaxFeatureElements)) {
          throw_invalid(q + ".elements", "must be in [1, " + num(kMaxFeatureElements) +
                                             "], edges across a narrow part" + got(term.elements));
        }
        term.h_min = positive(f.h_min(), q + ".h_min");
        term.h_max = at_least_h_min(f.h_max(), term.h_min, q + ".h_max");
        low = term.h_min;
        high = term.h_max;
        out.terms.emplace_back(term);
        break;
      }
      case v1::SizeTerm::KIND_NOT_SET:
        throw_invalid(p,
                      "no size term kind set; set exactly one of uniform, distance, grid, feature");
    }
    if (high < largest) largest = high, largest_term = i;
    if (low < smallest) smallest = low, smallest_term = i;
  }

  if (!terms.empty() && largest > limits.max_size_ratio * smallest) {
    throw_invalid("size", "h may vary by a factor up to " + num(largest / smallest) +
                              " (largest h " + num(largest) + " from size.terms[" +
                              std::to_string(largest_term) + "], smallest " + num(smallest) +
                              " from size.terms[" + std::to_string(smallest_term) + "]); at most " +
                              num(limits.max_size_ratio) +
                              " allowed: lower h_max or raise h_min (a grid's largest or "
                              "smallest value)");
  }
  if (request.size().has_gradation()) {
    const double g = request.size().gradation();
    if (!(g >= 0 && g <= kMaxGradation)) {
      throw_invalid("size.gradation", "must be 0 (none) or in (0, " + num(kMaxGradation) +
                                          "], the edge length's growth per length unit" + got(g));
    }
    out.gradation = g;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// DistMesh parameters: each optional, checked against the range its proto comment states.

Params params(const v1::MeshRequest& request) {
  Params out;
  if (!request.has_params()) return out;
  const auto& in = request.params();
  if (in.has_dptol()) out.dptol = in_range(in.dptol(), 0, true, 0.1, "params.dptol");
  if (in.has_ttol()) out.ttol = in_range(in.ttol(), 0, true, 1, "params.ttol");
  if (in.has_fscale()) {
    out.fscale = in_range(in.fscale(), 1, false, 2, "params.fscale");
    out.fscale_auto = false;
  }
  if (in.has_deltat()) out.deltat = in_range(in.deltat(), 0, true, 0.5, "params.deltat");
  if (in.has_geps()) out.geps = in_range(in.geps(), 0, true, 0.1, "params.geps");
  if (in.has_density_control_interval()) {
    out.density_control_interval =
        in_range(in.density_control_interval(), 0, 1000, "params.density_control_interval");
  }
  if (in.has_max_iterations()) {
    out.max_iterations = in_range(in.max_iterations(), 1, 1'000'000, "params.max_iterations");
  }
  if (in.has_cleanup()) out.cleanup = in.cleanup();
  if (in.has_multilevel())
    out.multilevel = in.multilevel() ? Params::Multilevel::kOn : Params::Multilevel::kOff;
  if (in.has_momentum()) out.momentum = in_range(in.momentum(), 0, false, 0.9, "params.momentum");
  return out;
}

// ---------------------------------------------------------------------------------------------
// The estimated node count, last: it needs the whole Problem.

// The h0 that aims the request at about `target` nodes, from the estimate `nodes` at its own h0
// (N scales as 1 / h0^2). At extreme h0 or size values the estimate over- or underflows (h0 =
// 1e-200 gives inf, 1e300 gives 0); then the estimate at compiled h0 = 1 serves, whose size field
// compile_problem has scaled to a smallest value of 1 (the request's h0 is that h0 over the
// field's smallest value). Not finite when even that gives no number.
double h0_for_nodes(const Problem& problem, const CompiledProblem& compiled, double nodes,
                    double target) {
  const double h0 = problem.h0 * std::sqrt(nodes / target);
  if (std::isfinite(h0) && h0 > 0) return h0;
  const double floor = size_field_range(problem.size).low;
  CompiledProblem unit = compiled;
  unit.h0 = 1.0;
  return std::sqrt(estimate_node_count(unit) / target) / floor;
}

std::string nodes_text(double nodes) {
  return std::isfinite(nodes) ? "about " + approx(nodes) : "more than 1e308";
}

// The engines draw the first points from a grid over the domain's box, spaced by the finest edge
// length (compiled h0 = h0 * the size field's smallest value), whatever part of the box the
// domain fills; the node estimate counts only the part inside. A domain that fills little of its
// box (two small disks far apart, a 1e4 x 1e-4 strip, whose grid row on the boundary is kept
// whole) would cost time and memory far beyond max_nodes: the grid may have up to
// kGridPointsPerNode points per node of the limit.
constexpr double kGridPointsPerNode = 64;

void check_initial_grid(const Problem& problem, const CompiledProblem& compiled,
                        const ConversionLimits& limits) {
  // Columns and rows as make_initial_grid counts them, give or take one each.
  const double spacing = compiled.h0;
  const double w = compiled.bbox.max.x - compiled.bbox.min.x;
  const double hgt = (compiled.bbox.max.y - compiled.bbox.min.y) / (std::sqrt(3.0) / 2);
  const double grid = (w / spacing + 1.5) * (hgt / spacing + 1.5);
  const double limit = kGridPointsPerNode * static_cast<double>(limits.max_nodes);
  if (grid <= limit) return;
  // The spacing s whose grid is at the limit: (w/s + 1.5)(h/s + 1.5) = limit, a quadratic in
  // 1/s; h0 scales with s.
  const double a = w * hgt, b = 1.5 * (w + hgt), c = 2.25 - limit;
  const double inverse = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double least = problem.h0 / (inverse * spacing);
  const Box& box = compiled.bbox;
  throw Error(
      ErrorCode::kResourceExhausted, "h0",
      "h0 = " + num(problem.h0) + " spaces the grid of initial points over the domain's box [" +
          num(box.min.x) + ", " + num(box.max.x) + "] x [" + num(box.min.y) + ", " +
          num(box.max.y) + "] by " + num(spacing) +
          " (h0 times the size field's smallest value): " + nodes_text(grid) +
          " points, more than the limit of " + approx(limit) + " (" + approx(kGridPointsPerNode) +
          " per node of the node limit); the domain fills little of its box: " +
          (std::isfinite(least) && least > 0 ? "h0 must be at least about " + approx(least)
                                             : "raise h0") +
          ", or mesh its parts one by one");
}

// Coordinates far from the origin compared with the finest edge lose the resolution that the
// loop needs: its finite-difference step for the distance gradient, deps * compiled h0
// (1.5e-8 of an edge), rounds away beyond about 1.3e8 edges from the origin. A unit disk at
// (2e7, 2e7) meshed at h0 = 0.1 came out with 11 nodes of 300, and no error. Up to kMaxReach
// edges the step stays above about 10 units in the last place.
constexpr double kMaxReach = 1e7;

void check_resolution(const Problem& problem, const CompiledProblem& compiled) {
  const Box& b = compiled.bbox;
  const double reach =
      std::max({std::fabs(b.min.x), std::fabs(b.max.x), std::fabs(b.min.y), std::fabs(b.max.y)});
  if (reach <= kMaxReach * compiled.h0) return;
  const double least = problem.h0 * reach / (kMaxReach * compiled.h0);
  throw_invalid("h0", "h0 = " + num(problem.h0) + " is too fine for a domain " + approx(reach) +
                          " from the origin (its box is [" + num(b.min.x) + ", " + num(b.max.x) +
                          "] x [" + num(b.min.y) + ", " + num(b.max.y) +
                          "]): the finest edge, h0 times the size field's smallest value = " +
                          num(compiled.h0) + ", must be at least " + approx(1 / kMaxReach) +
                          " times the largest coordinate; move the geometry towards the origin, "
                          "or h0 must be at least about " +
                          approx(least));
}

// A domain that is nowhere as thick as its finest edge holds no element of that size: DistMesh
// gave an empty mesh (fuzzing: a 2 x 6e-5 ellipse at h0 = 1.2e-3). An equilateral triangle of
// edge h needs an inscribed circle of radius h / (2 sqrt 3), about 0.29 h; the survey finds the
// depth from below, hence a quarter.
constexpr double kLeastDepthPerEdge = 0.25;

void check_thickness(const Problem& problem, const CompiledProblem& compiled, double depth) {
  const double edge = compiled.h0;
  if (depth >= kLeastDepthPerEdge * edge) return;
  const double most = problem.h0 * depth / (kLeastDepthPerEdge * edge);
  const std::string finest = "its finest edge (h0 times the size field's smallest value) is ";
  throw_invalid("h0", "h0 = " + num(problem.h0) + ": the domain is at most about " +
                          approx(2 * depth) + " thick, and " + finest + num(edge) +
                          ": no triangle of that size fits; h0 must be at most about " +
                          approx(most));
}

// `compiled`: compile_problem(problem), which throws on its own for an empty domain, a missing
// bbox or a fixed point outside. Keeps the survey's integral in `compiled`, so that the engine
// does not survey the domain again.
double check_node_count(const Problem& problem, CompiledProblem& compiled,
                        const ConversionLimits& limits, ThreadPool* pool) {
  const DomainSurvey survey = survey_domain(compiled, pool);
  compiled.inverse_size_integral = survey.inverse_size;
  const double nodes = survey.nodes;
  const double h0 = problem.h0;
  if (!(nodes >= 3)) {
    const double most = h0_for_nodes(problem, compiled, nodes, 3);
    throw_invalid("h0",
                  "h0 = " + num(h0) + " gives " + nodes_text(nodes) +
                      " nodes; at least 3 are needed: " +
                      (std::isfinite(most) && most > 0 ? "h0 must be at most about " + approx(most)
                                                       : "lower h0 or the size field's values"));
  }
  if (nodes > static_cast<double>(limits.max_nodes)) {
    const double least =
        h0_for_nodes(problem, compiled, nodes, static_cast<double>(limits.max_nodes));
    throw Error(
        ErrorCode::kResourceExhausted, "h0",
        "h0 = " + num(h0) + " gives " + nodes_text(nodes) + " nodes, more than the limit of " +
            std::to_string(limits.max_nodes) + ": " +
            (std::isfinite(least) && least > 0 ? "h0 must be at least about " + approx(least)
                                               : "raise h0 or the size field's smallest value"));
  }
  check_initial_grid(problem, compiled, limits);
  check_resolution(problem, compiled);
  check_thickness(problem, compiled, survey.depth);
  return nodes;
}

// ---------------------------------------------------------------------------------------------
// Job options: how the service runs the request.

JobOptions job_options(const v1::JobOptions& in, double estimated_nodes, bool volume,
                       const ConversionLimits& limits) {
  JobOptions out;
  switch (in.backend()) {
    case v1::JobOptions::BACKEND_AUTO:
      out.backend = Backend::kAuto;
      break;
    case v1::JobOptions::BACKEND_GPU:
      out.backend = Backend::kGpu;
      break;
    case v1::JobOptions::BACKEND_CPU:
      out.backend = Backend::kCpu;
      break;
    default:
      throw_invalid("options.backend", "must be BACKEND_AUTO, BACKEND_GPU or BACKEND_CPU (got " +
                                           std::to_string(in.backend()) + ")");
  }
  if (in.priority() < -10 || in.priority() > 10) {
    throw_invalid("options.priority",
                  "must be in [-10, 10] (got " + std::to_string(in.priority()) + ")");
  }
  out.priority = in.priority();
  out.snapshot_every = in_range(in.snapshot_every(), 0, 100'000, "options.snapshot_every");
  const int node_limit = volume ? volume_snapshot_nodes(limits) : limits.max_snapshot_nodes;
  out.snapshot_max_nodes =
      in.snapshot_max_nodes() == 0
          ? node_limit
          : in_range(in.snapshot_max_nodes(), 0, static_cast<uint32_t>(node_limit),
                     "options.snapshot_max_nodes");
  if (out.snapshot_every > 0 && estimated_nodes > static_cast<double>(out.snapshot_max_nodes)) {
    throw Error(ErrorCode::kResourceExhausted, "options.snapshot_every",
                "snapshots are limited to meshes of at most " +
                    std::to_string(out.snapshot_max_nodes) + " nodes and this one has about " +
                    approx(estimated_nodes) + ": set snapshot_every to 0 or raise h0");
  }
  out.timeout_s = in_range(in.timeout_s(), 0, false, 86'400, "options.timeout_s");
  if (in.label().size() > 128) {
    throw_invalid("options.label",
                  "at most 128 bytes (got " + std::to_string(in.label().size()) + ")");
  }
  out.label = in.label();
  return out;
}

}  // namespace

namespace {

// The request's fields, each checked, as a Problem (its node count not yet checked); `pool` as
// to_job_spec's.
Problem convert(const v1::MeshRequest& request, const ConversionLimits& limits, ThreadPool* pool) {
  Problem problem;

  if (request.has_volume()) {
    throw_invalid("volume", "a volume (3D) request; this entry point meshes plane domains");
  }
  if (!request.has_geometry()) {
    throw_invalid("geometry", "required: the domain to mesh (or volume, for a 3D domain)");
  }
  problem.geometry = ShapeConverter(limits, "geometry").convert(request.geometry());
  problem.size = size_field(request, limits);
  problem.h0 = positive(request.h0(), "h0");

  if (request.has_bbox()) {
    Box box{to_vec2(request.bbox().min(), "bbox.min"), to_vec2(request.bbox().max(), "bbox.max")};
    check_min_below_max(box.min, box.max, "bbox");
    problem.bbox = box;
  }

  const auto& points = request.fixed_points();
  if (points.size() > limits.max_fixed_points) {
    throw_invalid("fixed_points", "at most " + std::to_string(limits.max_fixed_points) +
                                      " fixed points allowed (got " +
                                      std::to_string(points.size()) + ")");
  }
  problem.fixed_points.reserve(points.size());
  for (int i = 0; i < points.size(); ++i) {
    problem.fixed_points.push_back(to_vec2(points[i], "fixed_points[" + std::to_string(i) + "]"));
  }

  // Once here, so that the worker meshes the sampled grids without sampling the field again.
  problem.size = sampled_size_field(problem, pool);

  problem.auto_corners = request.has_auto_corners() ? request.auto_corners() : true;
  problem.params = params(request);
  problem.seed = request.seed();
  return problem;
}

}  // namespace

Problem to_problem(const v1::MeshRequest& request, const ConversionLimits& limits) {
  Problem problem = convert(request, limits, nullptr);
  CompiledProblem compiled = compile_problem(problem);
  check_node_count(problem, compiled, limits, nullptr);
  return problem;
}

JobSpec to_job_spec(const v1::MeshRequest& request, const ConversionLimits& limits,
                    ThreadPool* pool) {
  JobSpec spec;
  if (request.has_volume()) {
    spec.volume = to_compiled_problem3(request, limits, spec.estimated_nodes);
  } else {
    const Problem problem = convert(request, limits, pool);
    spec.plane = compile_problem(problem);
    spec.estimated_nodes = check_node_count(problem, spec.plane, limits, pool);
  }
  spec.options =
      job_options(request.options(), spec.estimated_nodes, spec.volume.has_value(), limits);
  return spec;
}

}  // namespace meshd
