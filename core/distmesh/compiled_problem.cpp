#include "core/distmesh/compiled_problem.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>
#include <unordered_map>

#include "core/common/error.h"
#include "core/geometry/boundary_crossings.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"

namespace meshd {
namespace {

double box_diameter(const Box& b) { return std::hypot(b.max.x - b.min.x, b.max.y - b.min.y); }

// Points kept apart by more than `tol`: a hash of tol-sized cells, so that adding each of a
// long polygon's vertices costs O(1) rather than a pass over all the others.
class DistinctPoints {
 public:
  DistinctPoints(std::vector<Vec2>& points, double tol) : points_(points), tol_(tol) {
    for (size_t i = 0; i < points_.size(); ++i) cells_[cell_of(points_[i])].push_back(i);
  }

  // Appends p unless a point within `tol` is already there.
  void add(Vec2 p) {
    const Cell c = cell_of(p);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find({c.x + dx, c.y + dy});
        if (it == cells_.end()) continue;
        for (size_t i : it->second)
          if (norm(p - points_[i]) <= tol_) return;
      }
    cells_[c].push_back(points_.size());
    points_.push_back(p);
  }

 private:
  struct Cell {
    int64_t x, y;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const {
      return std::hash<int64_t>()(c.x * 0x9E3779B97F4A7C15ull ^ c.y);
    }
  };
  Cell cell_of(Vec2 p) const {
    // Clamped so that a far point with a tiny tolerance cannot overflow the cell index.
    auto index = [this](double v) {
      return static_cast<int64_t>(std::clamp(std::floor(v / tol_), -4e18, 4e18));
    };
    return {index(p.x), index(p.y)};
  }

  std::vector<Vec2>& points_;
  double tol_;
  std::unordered_map<Cell, std::vector<size_t>, CellHash> cells_;
};

}  // namespace

std::vector<Vec2> boundary_corners(const Program& geometry, const Box& bbox) {
  // Corners of the final boundary evaluate to 0 up to rounding in the primitives' parameters.
  const double tol = 1e-10 * box_diameter(bbox);
  std::vector<Vec2> corners;
  DistinctPoints distinct(corners, tol);
  auto add_if_on_boundary = [&](Vec2 v) {
    if (std::fabs(eval_sdf(geometry.view(), v)) <= tol) distinct.add(v);
  };
  // A vertex where the outline turns by less than a crossing must (a finely sampled curve)
  // is no corner: pinning every sample would force the mesh down to the sampling's spacing.
  const double min_sin = std::sin(kMinCrossingDegrees * std::numbers::pi / 180.0);
  for (const PrimitiveInfo& prim : geometry.primitives) {
    const size_t n = prim.corners.size() / 2;
    auto vertex = [&](size_t i) { return Vec2{prim.corners[2 * i], prim.corners[2 * i + 1]}; };
    for (size_t i = 0; i < n; ++i) {
      const Vec2 in = vertex(i) - vertex((i + n - 1) % n), out = vertex((i + 1) % n) - vertex(i);
      const bool turns =
          std::fabs(cross(in, out)) >= min_sin * norm(in) * norm(out) || dot(in, out) < 0.0;
      if (turns) add_if_on_boundary(vertex(i));
    }
  }
  // Where two primitives' boundaries cross on the final boundary, it turns: a corner too. Two
  // zigzag polygons can cross each other a million times; past kMaxCrossingCorners crossings the
  // request is refused rather than pinned node by node. The polygons' own corners do not count:
  // a real coastline has tens of thousands, as many as its outline has vertices.
  const size_t vertex_corners = corners.size();
  for (Vec2 v : boundary_crossings(geometry, bbox)) {
    add_if_on_boundary(v);
    if (corners.size() - vertex_corners > kMaxCrossingCorners) {
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
  DistinctPoints fixed(out.fixed_points, tol);
  for (size_t i = 0; i < problem.fixed_points.size(); ++i) {
    const Vec2 p = problem.fixed_points[i];
    const double d = eval_sdf(out.geometry.view(), p);
    if (d > geps) {
      std::ostringstream msg;
      msg << "must lie inside the domain or on its boundary (distance " << d << " > " << geps
          << " = geps * h0)";
      throw_invalid("fixed_points[" + std::to_string(i) + "]", msg.str());
    }
    fixed.add(p);
  }
  if (problem.auto_corners) {
    for (Vec2 c : boundary_corners(out.geometry, out.bbox)) fixed.add(c);
  }
  return out;
}

}  // namespace meshd
