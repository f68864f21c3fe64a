// Whether a closed triangle surface crosses itself, through CGAL's polygon mesh processing
// (exact predicates over a box-intersection sweep of the triangles' bounds).
//
// A surface that crosses itself has no inside that the pseudonormals' sign could follow: the
// distance stays exact, but which side a point is on depends on the triangle nearest to it, and
// the mesh comes out with flat or inverted tetrahedra where the sheets cross. Triangles that only
// share an edge or a vertex of the surface do not count.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

// Two triangles (indices into `triangles`, the lower first) that intersect other than along the
// edge or the vertex they share, or nothing. `triangles` must form a closed, consistently
// oriented 2-manifold of non-degenerate triangles over `vertices` (build_triangle_surface3
// checks that first); a vertex where two fans of triangles meet (the surface touching itself at
// a point) is reported as the crossing of one triangle of each fan.
std::optional<std::array<int32_t, 2>> find_surface_self_intersection3(
    const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
