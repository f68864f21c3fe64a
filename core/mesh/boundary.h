// The topological boundary of a triangle set: the edges that only one triangle uses.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace meshd {

// Returns the unique edges used by exactly one triangle, each oriented as in its triangle (so the
// triangle, and with counter-clockwise triangles the domain, lies on the edge's left). Edges used
// by two or more triangles, whatever their orientation, are interior (or non-manifold) and left
// out. The order is that of the triangles, then of the edges (t0,t1), (t1,t2), (t2,t0) within one.
//
// triangles: #M by 3 point indices (any non-negative values; no range check needed).
// Returns #E by 2 point indices.
std::vector<std::array<int32_t, 2>> boundary_edges_of(
    const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
