// The sharp edges that CSG creates where two primitives' surfaces meet (a bore through a plate, a
// boss on a face), found on the compiled program, as fixed points for DistMesh: without them the
// mesh rounds such an edge off by about one edge length, and its tetrahedra there are its worst.
//
// A grid of `spacing` over the domain's box marks where the nearest primitive (the one whose
// distance the program returns) changes between neighbouring samples near the boundary; from
// the midpoint, Newton steps on both primitives' distances at once find the point of their
// intersection curve nearby. A point is kept where it lies on the final boundary, the two
// surfaces meet there at more than kCreaseAngleDeg (a tangent contact is no edge), and no other
// fixed point lies within kCreaseGapFraction spacing of it: along a crease the kept points are
// that far to about twice that far apart.
#pragma once

#include <vector>

#include "core/common/vec3.h"
#include "core/geometry3d/program3d.h"

namespace meshd {

constexpr double kCreaseAngleDeg = 25.0;
constexpr double kCreaseGapFraction = 0.8;
// More grid samples than this: the grid is coarsened (a finer crease is then sampled more
// sparsely, never left out where the grid still sees it).
constexpr double kMaxCreaseGridSamples = 8e6;

// The crease points of `program` over `bounds` (finite), at about `spacing` (> 0) apart, none
// within kCreaseGapFraction spacing of `existing` (the primitives' own features).
std::vector<Vec3> crease_features3(const Program3& program, const Box3& bounds, double spacing,
                                   const std::vector<Vec3>& existing);

}  // namespace meshd
