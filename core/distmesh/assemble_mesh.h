// Turns an engine's final points and triangles into a Mesh: unused nodes dropped, boundary
// edges found and tagged by the primitive they lie on (the boundary groups of the output files).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/mesh/mesh.h"

namespace meshd {

// points: #N by 2; triangles: #M by 3 (either orientation; made counter-clockwise); boundary:
// boundary_half_edges(triangles) (core/mesh/boundary.h), found once by the caller for the
// clean-up too; tidy: every point is used and every triangle counter-clockwise already (the
// caller knows it), so the arrays move into the mesh as they are. Boundary groups are the
// primitives' names, in primitive order, that own at least one edge.
Mesh assemble_mesh(const CompiledProblem& problem, std::vector<Vec2> points,
                   std::vector<std::array<int32_t, 3>> triangles,
                   const std::vector<int32_t>& boundary, bool tidy = false);

}  // namespace meshd
