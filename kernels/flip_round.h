// The rounds of parallel Lawson flips that repair a triangulation on the device. A round: the
// candidates (edges failing the in-circle test) vote for their two triangles, the smallest edge
// id winning both so that every round makes progress; winners flip; flipped triangles re-link
// their outer neighbours. Undecided tests are listed for the host's exact predicate.
//
// Only the first round of a repair tests every edge. An edge's test depends on its two triangles
// alone, so a later round tests only the edges of the triangles on its work list: those that
// flipped in the round before and their neighbours, and those that had a candidate or an
// undecided test there. A graded job's repair cascades through 20-30 rounds of a few thousand
// flips among two million triangles; testing them all every round was most of its time.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec2.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// The work lists of the rounds, kept between jobs (the engine's arena). Rounds alternate between
// the two lists: one is read while the next round's is written.
struct FlipLists {
  DeviceBuffer<int32_t> work[2], work_stamp[2];  // a triangle's stamp: the round of its list
  DeviceBuffer<int32_t> voted, voted_stamp;      // the triangles a candidate voted for
};

// One round's views. `full`: test every edge (the first round of a repair, or one that the host
// drives), otherwise those of the round's work list.
struct FlipRound {
  DeviceSpan<const Vec2> p;
  DeviceSpan<Tri> tris, nbrs;
  DeviceSpan<int32_t> vote;           // #M, 0x7f7f7f7f between rounds
  DeviceSpan<int32_t> flipped_round;  // #M
  DeviceSpan<int32_t> partner;        // #M
  DeviceSpan<int32_t> undecided;      // the round's undecided edge ids (up to its size)
  TopologyCounters* counters;
  int32_t round;
  bool full;
  FlipLists* lists;
};

// Sizes the lists for #M triangles and forgets every stamp: at the start of a repair.
void reset_flip_lists(FlipLists& lists, int64_t m, cudaStream_t stream);

// The round's first half: opens it (or settles the batch, see TopologyCounters) and tests its
// edges, voting and listing.
void launch_flip_candidates(const FlipRound& r, cudaStream_t stream);
// Votes for the edges (ids 3 t + k) that the host decided to flip, between the two halves.
void launch_vote_edges(const FlipRound& r, DeviceSpan<const int32_t> edges, cudaStream_t stream);
// The second half: the flips, the links, the votes reset and the next round's list.
void launch_flips(const FlipRound& r, cudaStream_t stream);

}  // namespace meshd::gpu
