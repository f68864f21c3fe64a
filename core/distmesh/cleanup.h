// Boundary clean-up after convergence (see DISTMESH.md): DistMesh leaves slivers along curved
// and graded boundaries, triangles whose three nodes all lie on the boundary. Removing the node
// at the sliver's obtuse angle and relaxing again closes the gap to frontal methods' worst
// element without touching the interior, where DistMesh is already excellent.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

// Nodes to remove: for each sliver whose nodes all lie on the boundary (d > -geps), its node
// at the largest angle, unless fixed. points: #N by 2 (fixed first); triangles: #M by 3.
std::vector<int32_t> cleanup_victims(const CompiledProblem& problem,
                                     const std::vector<Vec2>& points,
                                     const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace meshd
