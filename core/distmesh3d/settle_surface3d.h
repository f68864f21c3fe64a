// The first part of the 3D finish: the mesh's surface nodes onto the boundary.
//
// The loop projects only the nodes that stepped outside, and the centroid filter drops the flat
// tetrahedra along the boundary, so a node of the final mesh's surface can lie inside: one that
// stopped short of the boundary, or one at the bottom of a pit whose cap (three nodes on the
// boundary, the fourth just under them) the filter dropped. Each such free node moves onto the
// boundary by the projection of step 8: to the nearest point or, where that turns a tetrahedron
// over, the projection of its surface neighbours' centre, or else the place on the boundary
// around the nearest point where its star's worst tetrahedron is best. A tetrahedron of its star
// whose other three nodes are on the surface too becomes a flat cap over the boundary by that
// move; one left under kCapQuality goes, as the centroid filter would have dropped it. Where no
// such place fits (each lays another tetrahedron flat or turns it over), the interior nodes of
// those tetrahedra step away from v's nearest point, and v goes there, when that leaves every
// tetrahedron they share positive. A node that still fits nowhere stays, counted as stuck; a few
// rounds give it another chance once its neighbours have moved.
//
// Measured (bench/RESULTS.md): the pits were 0.2-0.57 h0 deep; after this every surface node of
// the examples lies within 1e-7 h0 of the boundary, and the worst elements improved (the caps
// were slivers).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

// A cap whose radius ratio falls under this by the move goes.
constexpr double kCapQuality = 0.2;

struct SurfaceSettling {
  int64_t moved = 0;    // surface nodes moved onto the boundary
  int64_t dropped = 0;  // caps taken out
  int64_t stuck = 0;    // surface nodes off the boundary that could not move
};

// points: #N by 3, the first `fixed` never move; tets: #M by 4, positively oriented, loses the
// dropped caps (nodes no tetrahedron uses any more stay in points); step: the distance
// gradient's finite-difference step (absolute). pool: may be null; the result is the same for
// any number of threads.
SurfaceSettling settle_surface3d(const Domain3& domain, double step, std::vector<Vec3>& points,
                                 std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                                 ThreadPool* pool);

}  // namespace meshd
