// Delaunay tetrahedralization of a point set through CGAL (exact predicates), returned as arrays.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

// The finite Delaunay tetrahedra of `points` (#N by 3), #M by 4 point indices, each positively
// oriented: (b - a) . ((c - a) x (d - a)) > 0. Of points that coincide, only the lowest index
// appears in the tetrahedra.
// Cospherical points are split by CGAL's symbolic perturbation, so the result depends only on
// the points (their order in the result is CGAL's, the same for the same input).
std::vector<std::array<int32_t, 4>> delaunay_tetrahedralize(const std::vector<Vec3>& points);

}  // namespace meshd
