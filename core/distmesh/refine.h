// Midpoint refinement, which makes the loop multilevel.
//
// DistMesh relaxes like an explicit diffusion: the slowest, mesh-wide mode needs a number of
// iterations that grows with the node count (PyDistMesh: 3,414 on G2 at 10k nodes). Meshing at
// 2 h0 first, splitting its triangles into four, and relaxing again at h0 leaves the fine level
// only local work: its start is already equilateral with the right density, because halving
// every edge of a mesh that follows the relative size field keeps its grading.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

// Appends the midpoint of every edge of `triangles` longer than sqrt(2) times the edge that
// `problem` (the finer level) asks for there, h0 h(midpoint), to `points` (#N by 2, fixed nodes
// first and kept first). Midpoints of boundary edges are projected onto the boundary of
// `problem`. Returns the triangles split over their new midpoints (in four where all three
// edges are split, #4M by 3 for a mesh that follows its size field; counter-clockwise where
// `triangles` are): a triangulation of the new points where the projections moved no midpoint
// across a neighbour, which the engine completes and flips instead of triangulating from
// scratch. Edges already short enough stay whole: along a coast whose fixed vertices lie closer
// than the coarse edge, splitting every edge made each level four times denser there than its
// size field, and a region meshed in five levels came out with four times its node estimate.
std::vector<std::array<int32_t, 3>> refine_by_midpoints(
    const CompiledProblem& problem, std::vector<Vec2>& points,
    const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
