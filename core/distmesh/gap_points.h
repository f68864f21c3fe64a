// Nodes for the parts of the domain that a coarser level's mesh missed.
//
// A multilevel run (distmesh.cpp) starts at h0 * 2^k, where a lake or a lobe narrower than that
// level's edge gets no node, and midpoint refinement (refine.h) only splits the triangles it has:
// such a part stayed without mesh at every level. A coastline meshed in three levels lost six
// lakes of 0.17 to 0.26 km2, and a lobe of another lake was left out while a triangle reached
// across 450 m of land to the lake beyond it (its quality 0.095, the mesh's worst).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

// The points that `level`'s initial grid (initial_points.cuh) would keep in the domain and that
// lie outside every triangle of the coarse mesh (`coarse_points`, `coarse_triangles`): where the
// coarse mesh missed part of the domain. Empty where it covers the domain, which it does unless
// some part lies under its resolution. Tested over `pool`'s threads when one is given, with the
// same result.
std::vector<Vec2> uncovered_grid_points(const CompiledProblem& level,
                                        const std::vector<Vec2>& coarse_points,
                                        const std::vector<std::array<int32_t, 3>>& coarse_triangles,
                                        ThreadPool* pool = nullptr);

// Those of `points` farther than half the level's edge, h0 h / 2, from every node of `nodes`
// (the refined level's, which hold the coarse mesh's edges' midpoints): the nodes a gap needs.
std::vector<Vec2> away_from_nodes(const CompiledProblem& level, const std::vector<Vec2>& points,
                                  const std::vector<Vec2>& nodes);

}  // namespace meshd
