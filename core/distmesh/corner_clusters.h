// Corners too close together to all be mesh nodes.
//
// Every corner the compiler finds (boundary_corners) becomes a fixed node. Where an outline has
// several corners within a fraction of the local edge of each other (a coastline's vertices a
// few metres apart after its simplification, a CAD outline's tiny fillet segments), each pair
// of them makes an edge that short, and the triangles joining it to the edges of full length
// around are slivers that no node motion mends. Of such a cluster only the sharpest corner (the
// one where the domain's angle is farthest from straight) stays fixed; the boundary between the
// others is still followed through the distance function, just not pinned node by node.
#pragma once

#include <vector>

#include "core/common/vec2.h"
#include "core/geometry/program.h"
#include "core/geometry/size_program.h"

namespace meshd {

// Corners closer than this share of the local edge (h0 * h at the sharper corner) to a sharper
// one are not fixed.
constexpr double kCornerClusterShare = 0.25;

// `corners` without those within kCornerClusterShare * h0 * h of a sharper corner or of one of
// `kept` (fixed points the caller keeps whatever they are); the survivors in their given order.
// A corner's sharpness is |pi - the domain's angle there|: turns[i] (boundary_corners' turns),
// or where that is NaN the angle measured on a small circle around the corner, only where two
// corners are that close.
std::vector<Vec2> thin_corner_clusters(const std::vector<Vec2>& corners,
                                       const std::vector<double>& turns,
                                       const std::vector<Vec2>& kept, const Program& geometry,
                                       const SizeProgram& size, double h0);

}  // namespace meshd
