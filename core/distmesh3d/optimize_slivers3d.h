// Sliver removal: local optimisation of the worst tetrahedra, as the 2D clean-up does for
// triangles (core/distmesh/optimize_worst.h).
//
// DistMesh's forces equalise bar lengths, and four nodes at equal distances can still lie almost
// in a plane: a sliver, with q near 0 and dihedral angles near 0 and 180 degrees, which no force
// along the bars notices. Here each free node of a tetrahedron under kVisitBelowQuality3 moves,
// by a pattern search, to where its star is best: first its worst tetrahedron, up to
// kOptimizeBelowQuality3, then its mean. Interior nodes move in space, boundary nodes along the
// boundary (re-projected onto it). A move is taken only when it raises the star's score, so no
// tetrahedron turns over, the worst element can only improve, and the rest is untouched. Past
// the target a move only raises the mean: pushing the worst one further distorted the others,
// and visiting the nodes of fair tetrahedra too (q under 0.8) gives back more mean than the
// slivers' repair costs (a ball of 48k nodes: q_min 0.01 -> 0.54, q_mean 0.9371 -> 0.9381).
// The connectivity is kept: the result need not be Delaunay, which no solver asks. Each pass
// takes the nodes together in groups that share no tetrahedron, which move in parallel with the
// same result on any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

// The nodes of tetrahedra under kVisitBelowQuality3 move; a star's worst tetrahedron counts up to
// kOptimizeBelowQuality3, its mean beyond.
constexpr double kVisitBelowQuality3 = 0.8;
constexpr double kOptimizeBelowQuality3 = 0.6;

// points: #N by 3, the first `fixed` never move; tets: #M by 4, positively oriented; h0 > 0 and
// step (the distance gradient's, absolute) in the request's length unit. pool: null, or the
// threads that move nodes sharing no tetrahedron at once. Returns the number of moves made.
int64_t optimize_slivers3d(const Domain3& domain, double step, std::vector<Vec3>& points,
                           const std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                           ThreadPool* pool);

}  // namespace meshd
