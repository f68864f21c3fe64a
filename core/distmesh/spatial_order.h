// Nodes renumbered along a Hilbert curve.
//
// The GPU engine gives each thread one node, and a warp of 32 consecutive nodes walks the
// geometry's spatial indexes (bvh.h) and gathers its bars together: the closer those nodes lie,
// the fewer different tree nodes and bars the warp touches. Refinement appends every midpoint
// after the coarse nodes, in the order of its edge, so a warp of them can span a whole row of
// the domain; along a Hilbert curve it spans a few edges in each direction. The CPU engine's
// chunks of nodes gain the same locality in the cache.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec2.h"

namespace meshd {

// Reorders points[first_free..] (#N by 2) by their position along a Hilbert curve over their
// bounding box, keeping points[0..first_free) (the fixed nodes) where they are, and renumbers
// `triangles` (#M by 3, indices into points) to match. Ties keep their order, so equal inputs
// give equal outputs.
void hilbert_order(std::vector<Vec2>& points, int32_t first_free,
                   std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
