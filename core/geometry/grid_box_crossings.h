// Where a distance grid's zero level meets the sides of its own box: corners of the domain that a
// mask touching its image's border has (grid_sdf.cuh cuts the interpolant's negative set at the
// box). Along a side the interpolant is linear between samples, so each sign change gives its
// point exactly. A crossing where the zero level runs within kMinCrossingDegrees of the side
// (a tangent) gives none, as in boundary_crossings.h.
#pragma once

#include <vector>

#include "core/common/vec2.h"
#include "core/geometry/program.h"

namespace meshd {

// Appends to `out` (#K by 2) the crossings of the kGrid instruction `ins` of `program`, in world
// coordinates. Whether one lies on the final boundary is the caller's test.
void grid_box_crossings(const Program& program, const Instruction& ins, std::vector<Vec2>& out);

}  // namespace meshd
