#include "core/distmesh/compiled_problem.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>
#include <unordered_map>

#include "core/common/error.h"
#include "core/distmesh/corner_clusters.h"
#include "core/geometry/boundary_crossings.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry/feature_size.h"
#include "core/geometry/gradation.h"
#include "core/geometry/lipschitz.h"
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

  // Appends p unless a point within `tol` is already there; returns whether it did.
  bool add(Vec2 p) {
    const Cell c = cell_of(p);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find({c.x + dx, c.y + dy});
        if (it == cells_.end()) continue;
        for (size_t i : it->second)
          if (norm(p - points_[i]) <= tol_) return false;
      }
    cells_[c].push_back(points_.size());
    points_.push_back(p);
    return true;
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

std::vector<Vec2> boundary_corners(const Program& geometry, const Box& bbox,
                                   std::vector<double>* turns) {
  // Corners of the final boundary evaluate to 0 up to rounding in the primitives' parameters.
  const double tol = 1e-10 * box_diameter(bbox);
  std::vector<Vec2> corners;
  DistinctPoints distinct(corners, tol);
  if (turns != nullptr) turns->clear();
  auto add_if_on_boundary = [&](Vec2 v, double turn) {
    if (std::fabs(eval_sdf(geometry.view(), v)) <= tol && distinct.add(v) && turns != nullptr)
      turns->push_back(turn);
  };
  // A vertex where the outline turns by less than a crossing must (a finely sampled curve)
  // is no corner: pinning every sample would force the mesh down to the sampling's spacing.
  const double min_sin = std::sin(kMinCrossingDegrees * std::numbers::pi / 180.0);
  for (const PrimitiveInfo& prim : geometry.primitives) {
    const size_t n = prim.corners.size() / 2;
    auto vertex = [&](size_t i) { return Vec2{prim.corners[2 * i], prim.corners[2 * i + 1]}; };
    for (size_t i = 0; i < n; ++i) {
      const Vec2 in = vertex(i) - vertex((i + n - 1) % n), out = vertex((i + 1) % n) - vertex(i);
      const bool turning =
          std::fabs(cross(in, out)) >= min_sin * norm(in) * norm(out) || dot(in, out) < 0.0;
      if (turning)
        add_if_on_boundary(vertex(i), std::atan2(std::fabs(cross(in, out)), dot(in, out)));
    }
  }
  // Where two primitives' boundaries cross on the final boundary, it turns: a corner too. Two
  // zigzag polygons can cross each other a million times; past kMaxCrossingCorners crossings the
  // request is refused rather than pinned node by node. The polygons' own corners do not count:
  // a real coastline has tens of thousands, as many as its outline has vertices.
  const size_t vertex_corners = corners.size();
  for (Vec2 v : boundary_crossings(geometry, bbox)) {
    add_if_on_boundary(v, NAN);
    if (corners.size() - vertex_corners > kMaxCrossingCorners) {
      throw_invalid("geometry", "its primitives' boundaries cross at more than " +
                                    std::to_string(kMaxCrossingCorners) +
                                    " corners of the domain (at most " +
                                    std::to_string(kMaxCrossingCorners) + ")");
    }
  }
  return corners;
}

namespace {

// The box the initial points need: bbox when given, clipped to where the domain can be.
Box domain_box(const Program& geometry, const std::optional<Box>& bbox) {
  const Box derived = program_bounds(geometry);
  if (is_empty(derived))
    throw_invalid("geometry", "the domain is empty (its intersection is empty)");
  Box out;
  if (bbox) {
    out = *bbox;
  } else if (!is_bounded(derived)) {
    throw_invalid("bbox", "required: the geometry is unbounded (a half-plane is not cut off)");
  } else {
    out = derived;
  }
  if (is_bounded(derived)) {
    // The initial points only need the part of the box that the domain can occupy.
    out = {{std::max(out.min.x, derived.min.x), std::max(out.min.y, derived.min.y)},
           {std::min(out.max.x, derived.max.x), std::min(out.max.y, derived.max.y)}};
    if (is_empty(out)) throw_invalid("bbox", "does not overlap the geometry");
  }
  return out;
}

// A field without gradation, or a constant one, has nothing to limit.
bool limits_gradient(const SizeFieldSpec& spec) {
  return spec.gradation > 0 && std::any_of(spec.terms.begin(), spec.terms.end(), [](const auto& t) {
           return !std::holds_alternative<UniformSize>(t);
         });
}

bool needs_sampling(const SizeFieldSpec& spec) {
  return limits_gradient(spec) ||
         std::any_of(spec.terms.begin(), spec.terms.end(),
                     [](const auto& t) { return std::holds_alternative<FeatureSize>(t); });
}

// Feature-size terms become grids, then a gradation replaces the whole field by its limited
// grid. Both grids span `box` at half the finest edge, h0 * (the field's lower bound) / 2; the
// growth g of the edge h0 * h is g / h0 for h.
SizeFieldSpec sample_field(const SizeFieldSpec& spec, const Program& geometry, const Box& box,
                           double h0, ThreadPool* pool) {
  const double cell = 0.5 * h0 * size_field_range(spec).low;
  SizeFieldSpec out = spec;
  for (SizeTerm& term : out.terms) {
    if (const auto* f = std::get_if<FeatureSize>(&term))
      term = feature_size_grid(geometry, *f, box, cell, h0);
  }
  if (limits_gradient(out)) {
    GridSize limited =
        limited_size_grid(compile_size_field(out), box, cell, out.gradation / h0, pool);
    out.terms.clear();
    out.terms.emplace_back(std::move(limited));
  }
  out.gradation = 0;
  return out;
}

}  // namespace

SizeFieldSpec sampled_size_field(const Problem& problem, ThreadPool* pool) {
  if (!needs_sampling(problem.size)) return problem.size;
  const Program geometry = compile_geometry(problem.geometry);
  return sample_field(problem.size, geometry, domain_box(geometry, problem.bbox), problem.h0, pool);
}

CompiledProblem compile_problem(const Problem& problem) {
  CompiledProblem out;
  out.geometry = compile_geometry(problem.geometry);
  out.lipschitz = distance_lipschitz(out.geometry);
  out.bbox = domain_box(out.geometry, problem.bbox);
  out.size =
      compile_size_field(needs_sampling(problem.size) ? sample_field(problem.size, out.geometry,
                                                                     out.bbox, problem.h0, nullptr)
                                                      : problem.size);
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
    t.scale /= floor;
  }
  out.params = problem.params;
  if (out.params.fscale_auto)
    out.params.fscale = out.size.uniform() ? kUniformFscale : kGradedFscale;
  out.seed = problem.seed;

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
    std::vector<double> turns;
    const std::vector<Vec2> corners = boundary_corners(out.geometry, out.bbox, &turns);
    // The thinning reads the request's fixed points before any corner joins them.
    const std::vector<Vec2> thinned =
        thin_corner_clusters(corners, turns, out.fixed_points, out.geometry, out.size, out.h0);
    for (Vec2 c : thinned) fixed.add(c);
  }
  return out;
}

}  // namespace meshd
