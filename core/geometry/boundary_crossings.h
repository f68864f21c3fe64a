// Where the boundaries of two primitives of a compiled geometry cross: the candidates for the
// corners of a CSG shape that are no primitive's own vertex (a tooth meeting a disk, a channel's
// sides meeting, a circle cut by a line).
//
// Each primitive's boundary is a set of curves: the sides of a rectangle and a polygon
// (segments), a half-plane's line clipped to a box (a segment), a circle, an ellipse. Every pair
// of curves of two different primitives is intersected in closed form where one exists
// (segment-segment, segment-circle, circle-circle, and the ellipse with a segment, solved in the
// ellipse's own frame where it is a unit circle); the ellipse with a circle or another ellipse,
// a quartic, by bracketing the sign changes of the other curve's implicit function along the
// ellipse's angle at 1024 samples and bisecting each to the last bit. Curves that touch without
// crossing (tangents) or cross at under kMinCrossingDegrees give no point: the boundary does not
// turn there. A distance grid adds no curve (its zero level meets other boundaries undetected);
// it adds where its zero level meets its own box (grid_box_crossings.h).
#pragma once

#include <vector>

#include "core/common/vec2.h"
#include "core/geometry/program.h"

namespace meshd {

// Below this angle between two boundaries a crossing is no corner worth a fixed node.
constexpr double kMinCrossingDegrees = 5.0;

// Every crossing of two different primitives' boundaries within `box` (#K by 2, unordered, with
// repeats where several pairs meet at one point). Whether a crossing lies on the final
// boundary is the caller's test: most crossings of a CSG tree end up inside or outside it.
std::vector<Vec2> boundary_crossings(const Program& geometry, const Box& box);

}  // namespace meshd
