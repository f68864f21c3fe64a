// Step 3 of the 3D loop: the Delaunay tetrahedra kept inside the domain, their bars, and each
// node's bars for the force sums.
//
// Invariants: bars are unique, each (lo, hi) with lo < hi, sorted; bar_offsets/bar_ends is a CSR
// of each node's incident bars: for node n, entries bar_offsets[n] .. bar_offsets[n + 1] - 1 of
// bar_ends hold 2 b for each bar b that starts at n and 2 b + 1 for each that ends there, in bar
// order, so that a node's force is summed in the same order on any number of threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

struct Topology3 {
  std::vector<std::array<int32_t, 4>> tets;  // #M by 4, positively oriented, kept inside
  std::vector<std::array<int32_t, 2>> bars;  // #B by 2, unique, lo < hi, sorted
  std::vector<int64_t> bar_offsets;          // #N + 1
  std::vector<int64_t> bar_ends;             // #2B
  // Free nodes closer than the coincidence distance to another node, increasing: a node the
  // projection put onto a fixed corner, with which it makes only flat tetrahedra (dropped by the
  // centroid filter, so no bar between them lets density control see the pair).
  std::vector<int32_t> coincident;
};

// Tetrahedralizes `points` (#N by 3, the first `fixed` fixed) and keeps the tetrahedra whose
// centroid lies deeper than `depth` (> 0, the request's length unit) inside `domain`; lists the
// free nodes within `coincidence` (the same unit) of another node (of two free ones, the higher).
Topology3 triangulate3d(const Domain3& domain, const std::vector<Vec3>& points, int64_t fixed,
                        double depth, double coincidence, ThreadPool* pool);

// The same from `all`, the Delaunay tetrahedra of `points` (delaunay3d.h), already built.
Topology3 topology_of3d(const Domain3& domain, const std::vector<Vec3>& points,
                        const std::vector<std::array<int32_t, 4>>& all, int64_t fixed, double depth,
                        double coincidence, ThreadPool* pool);

// The threads of `pool`, 1 for none.
unsigned pool_threads(ThreadPool* pool);

// The unique bars of `tets` and the CSR of each of the `nodes` nodes' bars, as Topology3 holds
// them; `pool` (may be null) shares the sorting.
void build_bars3d(Topology3& topology, int64_t nodes, ThreadPool* pool = nullptr);

}  // namespace meshd
