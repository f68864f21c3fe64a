// Repair of a triangulation in which a node crossed an edge since it was made.
//
// Such a node turns triangles over, and Lawson's flips cannot undo a fold: until now the engines
// triangulated every node again, a second or more per million nodes, for a defect a few
// triangles wide. The fold is local. Cutting out every triangle that shares a node with a
// turned-over one leaves a valid partial triangulation around a hole, and the completion
// (complete_triangulation.h) fills the hole from its boundary and the nodes inside it, widening
// it where its first fill fails a check.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"

namespace meshd {

// Removes from `tri` (with neighbours; -1 across the removed ones after) every triangle that
// shares a node with one turned over or flat for `points` (#N by 2, exact predicates). Returns
// whether there was any.
bool cut_folds(const std::vector<Vec2>& points, Triangulation& tri);

// cut_folds, then the completion of what is left: a triangulation of the convex hull of
// `points`, or an empty one when `tri` has no fold or the completion fails (then the caller
// triangulates from scratch). `always_gap` as in complete_triangulation. Not Delaunay in
// general: flip it (lawson_repair.h or the GPU engine's repair).
Triangulation refill_folds(const std::vector<Vec2>& points, Triangulation tri, int32_t always_gap);

}  // namespace meshd
