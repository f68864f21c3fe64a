// The finish's smoothing: a few sweeps of smart Laplacian moves that raise the mean quality.
//
// DistMesh's equilibrium equalises bars against the size field; it is not where the triangles
// are best. Where the boundary is long and curved (a coastline: a third of the triangles touch
// it) or the field grades fast, the mean quality settles near 0.96; moving each node to the mean
// of its neighbours, where that raises its star's mean quality, recovers most of the rest
// (the coastal DistMesh tools' "direct smoothing"). Boundary nodes move the same way, then onto
// the boundary, so they slide along it. A move is taken only when every triangle of the star
// stays at or above kOptimizeBelowQuality (optimize_worst.h) and the star's mean rises; nodes of
// triangles under that threshold are left to the worst-element optimisation, which runs after.
// So no triangle falls under the threshold, the triangles the optimisation starts from stay
// those under it, and the mesh stays valid. Nodes sharing no triangle move at once, in parallel,
// with the same result for any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/distmesh/compiled_problem.h"

namespace meshd {

class ThreadPool;

// Nodes of triangles under this radius ratio are smoothed; a mesh near perfect costs little.
constexpr double kSmoothBelowQuality = 0.99;

// points: #N by 2, fixed nodes first (never moved); triangles: #M by 3, counter-clockwise;
// boundary: boundary_half_edges(triangles) (core/mesh/boundary.h). Points no triangle uses are
// left alone. pool: null, or the threads that move nodes sharing no triangle at once. Returns
// the number of node moves made.
int64_t smooth_mean_quality(const CompiledProblem& problem, std::vector<Vec2>& points,
                            const std::vector<std::array<int32_t, 3>>& triangles,
                            const std::vector<int32_t>& boundary, ThreadPool* pool = nullptr);

}  // namespace meshd
