// The mesh as the finish's node moves see it (smooth_mean_quality.h, optimize_worst.h): the
// points they move, the triangles they keep, the stars of the nodes they look at, which nodes lie
// on the boundary, and the domain's distance that keeps a move, and the triangles around it, inside
// the domain or on its boundary.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/star_table.h"

namespace meshd {

class ThreadPool;

class NodeMoves {
 protected:
  // points: #N by 2, fixed nodes first; triangles: #M by 3, counter-clockwise; boundary:
  // boundary_half_edges(triangles) (core/mesh/boundary.h).
  NodeMoves(const CompiledProblem& problem, std::vector<Vec2>& points,
            const std::vector<std::array<int32_t, 3>>& triangles,
            const std::vector<int32_t>& boundary, ThreadPool* pool);

  // t's radius ratio, negative where it turned over.
  double quality(int32_t t) const;
  // `nodes` (increasing, their stars added) in groups of which no two share a triangle
  // (colour_groups.h): a group's nodes move at once.
  std::vector<std::vector<int32_t>> colour_groups(const std::vector<int32_t>& nodes) const;
  // Whether x lies on the domain's boundary, within kOnBoundaryTolerance.
  bool lies_on_boundary(Vec2 x) const;
  // Whether, with v at x (where the distance is d_at_x), every triangle of v's star keeps its
  // centroid inside by more than geps: the centroid filter's rule (centroid_rule.cuh), which held
  // when the mesh came in. Triangles cross a spit of land where it is narrower than an edge, with
  // their centroids in the water; a node moved a little, or carried along the boundary round the
  // spit's tip, can put one on it. Far inside, the distance's bound at x decides without the
  // centroids' (the distance grows by at most CompiledProblem::lipschitz times the way from x to
  // a centroid).
  bool star_stays_inside(int32_t v, Vec2 x, double d_at_x) const;

  // A boundary node this close (times h0) to the domain's boundary is on it: the snap moves
  // nodes farther off onto it, and a move keeps a boundary node this close.
  static constexpr double kOnBoundaryTolerance = 1e-4;

  ThreadPool* pool_;
  ProgramView fd_;
  double h0_;
  double deps_;
  double geps_;
  double lipschitz_;
  int32_t nfix_;
  std::vector<Vec2>& p_;
  const std::vector<std::array<int32_t, 3>>& t_;
  StarTable stars_;
  std::vector<char> on_boundary_;
};

}  // namespace meshd
