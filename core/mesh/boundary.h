// The topological boundary of a triangle set: the edges that only one triangle uses.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace meshd {

// Returns the ids 3 t + k, increasing, of the half-edges that no other triangle uses, where
// half-edge 3 t + k runs from t[k] to t[(k + 1) % 3]. Edges used by two or more triangles,
// whatever their orientation, are interior (or non-manifold) and left out. The result does not
// change when the points are renumbered one-to-one or a triangle is turned over (its half-edge
// 3 t + k becomes 3 t + 2 - k), so one call serves every later form of the same triangles.
//
// triangles: #M by 3 point indices (any non-negative values; no range check needed).
// Returns #E ids.
std::vector<int32_t> boundary_half_edges(const std::vector<std::array<int32_t, 3>>& triangles);

// The ends of the given half-edges, in the given order: #E by 2 point indices.
// ids: #E half-edge ids 3 t + k as above, each below 3 #M.
std::vector<std::array<int32_t, 2>> half_edge_ends(
    const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<int32_t>& ids);

// Returns the unique edges used by exactly one triangle, each oriented as in its triangle (so the
// triangle, and with counter-clockwise triangles the domain, lies on the edge's left), in the
// order of boundary_half_edges.
//
// triangles: #M by 3 point indices (any non-negative values; no range check needed).
// Returns #E by 2 point indices.
std::vector<std::array<int32_t, 2>> boundary_edges_of(
    const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
