// Midpoint refinement, which makes the loop multilevel.
//
// DistMesh relaxes like an explicit diffusion: the slowest, mesh-wide mode needs a number of
// iterations that grows with the node count (PyDistMesh: 3,414 on G2 at 10k nodes). Meshing at
// 2 h0 first, splitting every triangle into four, and relaxing again at h0 leaves the fine level
// only local work: its start is already equilateral with the right density, because halving
// every edge keeps the relative size field's grading.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

// Appends the midpoint of every edge of `triangles` to `points` (#N by 2, fixed nodes first and
// kept first). Midpoints of boundary edges are projected onto the boundary of `problem`. Returns
// the triangles split in four (#4M by 3, counter-clockwise where `triangles` are): a
// triangulation of the new points where the projections moved no midpoint across a neighbour,
// which the engine completes and flips instead of triangulating from scratch.
std::vector<std::array<int32_t, 3>> refine_by_midpoints(
    const CompiledProblem& problem, std::vector<Vec2>& points,
    const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
