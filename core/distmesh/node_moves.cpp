#include "core/distmesh/node_moves.h"

#include <cmath>

#include "core/common/colour_groups.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/boundary.h"
#include "core/mesh/radius_ratio.cuh"

namespace meshd {

NodeMoves::NodeMoves(const CompiledProblem& problem, std::vector<Vec2>& points,
                     const std::vector<std::array<int32_t, 3>>& triangles,
                     const std::vector<int32_t>& boundary, ThreadPool* pool)
    : pool_(pool),
      fd_(problem.geometry.view()),
      h0_(problem.h0),
      deps_(problem.params.deps * problem.h0),
      geps_(problem.params.geps * problem.h0),
      lipschitz_(problem.lipschitz),
      nfix_(static_cast<int32_t>(problem.fixed_points.size())),
      p_(points),
      t_(triangles),
      stars_(points.size(), triangles, pool),
      on_boundary_(points.size(), 0) {
  for (const auto& e : half_edge_ends(triangles, boundary))
    on_boundary_[e[0]] = on_boundary_[e[1]] = 1;
}

double NodeMoves::quality(int32_t t) const {
  const auto& tri = t_[t];
  return oriented_radius_ratio(p_[tri[0]], p_[tri[1]], p_[tri[2]]);
}

std::vector<std::vector<int32_t>> NodeMoves::colour_groups(
    const std::vector<int32_t>& nodes) const {
  return meshd::colour_groups(nodes, [&](int32_t v, auto&& visit) {
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t)
      for (int32_t u : t_[*t]) visit(u);
  });
}

bool NodeMoves::lies_on_boundary(Vec2 x) const {
  return std::fabs(eval_sdf(fd_, x)) <= kOnBoundaryTolerance * h0_;
}

bool NodeMoves::star_stays_inside(int32_t v, Vec2 x, double d_at_x) const {
  for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t) {
    Vec2 sum{0.0, 0.0};
    for (int32_t u : t_[*t]) sum = sum + (u == v ? x : p_[u]);
    const Vec2 centroid = (1.0 / 3.0) * sum;
    if (d_at_x + lipschitz_ * norm(centroid - x) < -geps_) continue;
    if (!(eval_sdf(fd_, centroid) < -geps_)) return false;
  }
  return true;
}

}  // namespace meshd
