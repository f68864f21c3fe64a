// Repair of a Delaunay triangulation whose points moved a little, by Lawson's edge flips.
//
// DistMesh retriangulates after every ttol * h0 of drift, yet consecutive triangulations differ
// in well under 1% of their triangles. As long as no triangle became inverted, flipping every
// edge that fails the in-circle test until none does reaches the Delaunay triangulation of the
// new positions (in 2D Lawson's algorithm cannot get stuck). The predicates are CGAL's filtered
// exact ones, so nearly co-circular quadruples never make it cycle.
#pragma once

#include <cstdint>
#include <vector>

#include "core/delaunay/delaunay.h"

namespace meshd {

// Flips edges of `tri` (triangles and neighbours updated in place) until it is Delaunay for
// `points` (#N by 2). Triangles that turned over or flat are dropped first when they are
// expendable: outside the domain (keep[t] == 0, #M), or slivers with all three nodes on the
// boundary (on_boundary, #N), which collapse when their middle node is projected back onto a
// convex curve. DistMesh discards both anyway, and the rest stays a valid triangulation of a
// slightly smaller region. Fails, without changing anything, when any other triangle is
// inverted or flat: then the caller must triangulate from scratch.
struct RepairResult {
  bool ok = false;
  int64_t flips = 0;
  int64_t dropped = 0;  // expendable triangles removed
};
RepairResult lawson_repair(const std::vector<Vec2>& points, const std::vector<char>& keep,
                           const std::vector<char>& on_boundary, Triangulation& tri);

}  // namespace meshd
