// Neighbours of the triangles of a triangulation given by its vertex triples alone, in the
// convention of delaunay.h: the triangle across the edge opposite vertex k, -1 on the boundary.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshd {

// Fills `neighbors` (#M by 3) for `triangles` (#M by 3 point indices in [0, n), all oriented
// alike). Returns false when some edge is used by more than two triangles or twice in the same
// direction: the triangles do not form a triangulation. Linear time; at most 2^30 / 3 triangles.
bool triangle_neighbors(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                        std::vector<std::array<int32_t, 3>>& neighbors);

}  // namespace meshd
