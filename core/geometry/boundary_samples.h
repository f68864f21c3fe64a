// Points along a 2D domain's boundary about a given spacing apart, without following the curves
// one by one: what pins the rims of an extruded profile in 3D (sharp_features3.h).
#pragma once

#include <vector>

#include "core/common/vec2.h"
#include "core/geometry/program.h"

namespace meshd {

// `corners` first (kept as they are), then points where the boundary crosses the edges of a
// grid a quarter of `spacing` fine over `box` (which must hold the domain), each projected onto
// the boundary, kept where no point already kept lies within 0.75 spacing: neighbours along a
// curve end up between 0.75 and 1.5 spacing apart. spacing > 0; the grid is coarsened to at most
// kMaxBoundaryGridPoints vertices.
std::vector<Vec2> boundary_samples(const Program& program, const Box& box, double spacing,
                                   const std::vector<Vec2>& corners);
constexpr double kMaxBoundaryGridPoints = 4e6;

}  // namespace meshd
