#include "core/distmesh/compiled_problem.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/common/error.h"
#include "core/geometry/boundary_crossings.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"

namespace meshd {
namespace {

double box_diameter(const Box& b) { return std::hypot(b.max.x - b.min.x, b.max.y - b.min.y); }

// Appends p unless a point within `tol` is already there.
void add_unique(std::vector<Vec2>& points, Vec2 p, double tol) {
  for (Vec2 q : points)
    if (norm(p - q) <= tol) return;
  points.push_back(p);
}

}  // namespace

std::vector<Vec2> boundary_corners(const Program& geometry, const Box& bbox) {
  // Corners of the final boundary evaluate to 0 up to rounding in the primitives' parameters.
  const double tol = 1e-10 * box_diameter(bbox);
  std::vector<Vec2> corners;
  auto add_if_on_boundary = [&](Vec2 v) {
    if (std::fabs(eval_sdf(geometry.view(), v)) <= tol) add_unique(corners, v, tol);
  };
  for (const PrimitiveInfo& prim : geometry.primitives) {
    for (size_t i = 0; i + 1 < prim.corners.size(); i += 2)
      add_if_on_boundary({prim.corners[i], prim.corners[i + 1]});
  }
  // Where two primitives' boundaries cross on the final boundary, it turns: a corner too. Two
  // zigzag polygons can cross each other a million times; past kMaxCrossingCorners the request
  // is refused rather than pinned node by node (the duplicate test above is quadratic).
  for (Vec2 v : boundary_crossings(geometry, bbox)) {
    add_if_on_boundary(v);
    if (corners.size() > kMaxCrossingCorners) {
      throw_invalid("geometry", "its primitives' boundaries cross at more than " +
                                    std::to_string(kMaxCrossingCorners) +
                                    " corners of the domain (at most " +
                                    std::to_string(kMaxCrossingCorners) + ")");
    }
  }
  return corners;
}

CompiledProblem compile_problem(const Problem& problem) {
  CompiledProblem out;
  out.geometry = compile_geometry(problem.geometry);
  out.size = compile_size_field(problem.size);
  out.h0 = problem.h0;
  // The engines read h0 as the finest edge: they space the first points h0 apart and thin them
  // by (smallest h / h)^2, as distmesh2d.m does. The API means edge = h0 * h(p) (a uniform 0.5
  // halves the edges). Fold the field's lower bound into h0 so that both agree wherever the
  // bound is reached (every term reaches it when its shape touches the domain).
  double floor = out.size.terms.empty() ? 1.0 : INFINITY;
  for (const SizeTermCode& t : out.size.terms) floor = std::min(floor, t.h_min);
  out.h0 *= floor;
  for (SizeTermCode& t : out.size.terms) {
    t.h_min /= floor;
    t.slope /= floor;
    t.h_max /= floor;
  }
  out.params = problem.params;
  if (out.params.fscale_auto)
    out.params.fscale = out.size.uniform() ? kUniformFscale : kGradedFscale;
  out.seed = problem.seed;

  const Box derived = program_bounds(out.geometry);
  if (is_empty(derived))
    throw_invalid("geometry", "the domain is empty (its intersection is empty)");
  if (problem.bbox) {
    out.bbox = *problem.bbox;
  } else if (!is_bounded(derived)) {
    throw_invalid("bbox", "required: the geometry is unbounded (a half-plane is not cut off)");
  } else {
    out.bbox = derived;
  }
  if (is_bounded(derived)) {
    // The initial points only need the part of the box that the domain can occupy.
    out.bbox = {{std::max(out.bbox.min.x, derived.min.x), std::max(out.bbox.min.y, derived.min.y)},
                {std::min(out.bbox.max.x, derived.max.x), std::min(out.bbox.max.y, derived.max.y)}};
    if (is_empty(out.bbox)) throw_invalid("bbox", "does not overlap the geometry");
  }

  const double geps = problem.params.geps * problem.h0;
  const double tol = 1e-10 * box_diameter(out.bbox);
  for (size_t i = 0; i < problem.fixed_points.size(); ++i) {
    const Vec2 p = problem.fixed_points[i];
    const double d = eval_sdf(out.geometry.view(), p);
    if (d > geps) {
      std::ostringstream msg;
      msg << "must lie inside the domain or on its boundary (distance " << d << " > " << geps
          << " = geps * h0)";
      throw_invalid("fixed_points[" + std::to_string(i) + "]", msg.str());
    }
    add_unique(out.fixed_points, p, tol);
  }
  if (problem.auto_corners) {
    for (Vec2 c : boundary_corners(out.geometry, out.bbox)) add_unique(out.fixed_points, c, tol);
  }
  return out;
}

}  // namespace meshd
