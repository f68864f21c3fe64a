// Delaunay triangulation of a point set through CGAL (exact predicates), returned as arrays.
//
// Each triangle carries its three neighbours, so that the DistMesh bar list (the edges of the
// triangles kept inside the domain) needs no sort and no hash, and so that a triangulation of
// points that moved a little can be repaired by edge flips (lawson_repair.h) instead of rebuilt.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec2.h"

namespace meshd {

struct Triangulation {
  std::vector<std::array<int32_t, 3>> triangles;  // #M by 3, counter-clockwise
  // #M by 3: neighbors[t][k] is the triangle across the edge opposite triangles[t][k], -1 when
  // that edge is on the outer boundary.
  std::vector<std::array<int32_t, 3>> neighbors;
};

// Delaunay triangulation of `points` (#N by 2); duplicate points are kept out of the triangles.
Triangulation delaunay_triangulate(const std::vector<Vec2>& points);

// Constrained Delaunay triangulation of `points` (#N by 2) in which every segment of
// `constraints` (#C by 2 point indices) is an edge, unless one passes through another point;
// empty when two constraints cross or an end coincides with another point.
Triangulation constrained_delaunay_triangulate(
    const std::vector<Vec2>& points, const std::vector<std::array<int32_t, 2>>& constraints);

// Removes the triangles t with drop[t] (#M), renumbering the rest in order; their neighbours
// see -1 across the edges they shared with a removed one.
void drop_triangles(Triangulation& tri, const std::vector<char>& drop);

// The edges that bound at least one triangle t with keep[t], each once. keep: #M.
std::vector<std::array<int32_t, 2>> edges_of_kept(const Triangulation& tri,
                                                  const std::vector<char>& keep);

}  // namespace meshd
