// Delaunay triangulation of a point set through CGAL (exact predicates), returned as arrays.
//
// The edge list comes straight from the triangulation, each edge once with the triangles on its
// two sides, so that the DistMesh bar list (the edges of the triangles kept inside the domain)
// needs no sort and no hash: an edge is a bar when either side is kept.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec2.h"

namespace meshd {

struct Triangulation {
  std::vector<std::array<int32_t, 3>> triangles;   // #M by 3, counter-clockwise
  std::vector<std::array<int32_t, 2>> edges;       // #E by 2, each edge once
  std::vector<std::array<int32_t, 2>> edge_faces;  // #E by 2, triangle indices, -1 off the hull
};

// Delaunay triangulation of `points` (#N by 2); duplicate points are kept out of the triangles.
Triangulation delaunay_triangulate(const std::vector<Vec2>& points);

}  // namespace meshd
