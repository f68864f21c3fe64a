// The last step of the clean-up: local optimisation of the worst elements.
//
// DistMesh's forces equalise bar lengths, which is right in the interior and wrong at a sharp
// corner, where the single triangle at the corner needs two equal legs along the two sides.
// Here each node of a triangle under a quality target moves, by a pattern search, to where the
// worst triangle around it is best: interior nodes in the plane, boundary nodes along the
// boundary (re-projected onto it). A move is taken only when it raises the minimum quality of
// the node's star and keeps every triangle there positively oriented, so the mesh stays valid,
// the worst element can only improve, and the rest of the mesh is untouched. Before that, nodes
// of the mesh's boundary that lie off the domain's boundary (a node sagging next to a concave
// corner) are projected onto it wherever their star stays valid. Each pass takes the nodes of
// the triangles under the target together, in groups of nodes that share no triangle: a group's
// nodes move independently of each other, so they move in parallel.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

class ThreadPool;

// Triangles under this radius ratio have their nodes optimised.
constexpr double kOptimizeBelowQuality = 0.8;

// points: #N by 2, fixed nodes first (never moved); triangles: #M by 3, counter-clockwise;
// boundary: boundary_half_edges(triangles) (core/mesh/boundary.h), whose ends move along the
// boundary; below: null, or the triangles, increasing, that are turned over or under
// kOptimizeBelowQuality (oriented_radius_ratio, radius_ratio.cuh) as the points stand, when the
// caller knows them: then only those and the triangles around moved nodes are measured, with the
// same result. pool: null, or the threads that optimise nodes sharing no triangle at once (the
// result is the same for any number of threads). Returns the number of node moves made.
int64_t optimize_worst_elements(const CompiledProblem& problem, std::vector<Vec2>& points,
                                const std::vector<std::array<int32_t, 3>>& triangles,
                                const std::vector<int32_t>& boundary,
                                const std::vector<int32_t>* below = nullptr,
                                ThreadPool* pool = nullptr);

}  // namespace meshd
