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
//
// The kernels read their arguments from a FlipBatch in device memory and count the rounds there,
// so that one cooperative launch runs a repair's rounds until one finds no candidate, with no
// host round trip in between (launch_flip_loop). A repair may launch its rounds right behind its
// orientation check (launch_check_orientation): where that found a triangle turned over fatally,
// the rounds flip nothing, and the host, reading the counters once, rebuilds. The triangles it
// drops stand as walls (FlipBatch::walls), neither flipped nor flipped across, while the rounds
// repair the rest; the host removes them afterwards. Removing them first, as boundary, made a
// repair that dropped any two passes of rounds with a read in between.
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

// In device memory, written by the host once per repair (the views) and by the kernels.
struct FlipBatch {
  DeviceSpan<const Vec2> p;
  DeviceSpan<Tri> tris, nbrs;
  DeviceSpan<int32_t> vote;           // #M, 0x7f7f7f7f between rounds
  DeviceSpan<int32_t> flipped_round;  // #M
  DeviceSpan<int32_t> partner;        // #M
  DeviceSpan<int32_t> undecided;      // the round's undecided edge ids (up to its size)
  // #M, or empty: the triangles the orientation check dropped (0), left alone by the rounds.
  // Without walls, a dropped triangle stops the rounds as a fatal one does.
  DeviceSpan<const uint8_t> walls;
  TopologyCounters* counters;
  int32_t *work[2], *work_stamp[2], *voted, *voted_stamp;  // FlipLists
  int32_t rounds_per_launch;  // the loop ends after this many rounds (the host relaunches)
  int32_t full;  // the next round tests every edge (the first of a repair, or one the host drives)
  int32_t tail_items;  // the loop leaves a round with at most this many triangles to one block
  // Written by the kernels only: the host's copy of the fields above ends here.
  int32_t round;       // the current round's number, counted on the device for the engine's life
  int32_t round_full;  // the current round tests every edge
  int32_t rounds;      // rounds a loop on the device has run since its launch
  int32_t again;       // the cooperative loop's decision, for every thread of its grid
  int32_t tail;        // the loop's rounds have gone to block 0 alone (tail_items)
};

// Rounds one launch of the loop runs at most, unless told otherwise: a repair that needs more
// is launched again (a slow cascade along a long chain flips one edge a round: G5's finest level
// at 16M nodes needed more than 200).
constexpr int32_t kLoopFlipRounds = 200;

// Sizes the lists for #M triangles (their stamps are reset by launch_begin_flips).
void size_flip_lists(FlipLists& lists, int64_t m);
// A repair's start, in one launch rather than a copy and five memsets (a small job's repairs are
// bound by the host's calls): `batch` takes the host's part of `views` (up to `round`), the
// counters go to zero, every vote opens and every stamp is forgotten (set below any round).
void launch_begin_flips(const FlipBatch& views, FlipBatch* batch, cudaStream_t stream);

// The round's first half: opens it (or settles a batch launched one round at a time, see
// TopologyCounters) and tests its edges, voting and listing. `blocks`: a fixed grid (the kernels
// stride over their lists, whose lengths live on the device).
void launch_flip_candidates(FlipBatch* batch, int64_t blocks, cudaStream_t stream);
// The same for a round the host drives: it tests every edge and counts afresh, whatever the
// rounds before it settled on.
void launch_full_flip_candidates(FlipBatch* batch, int64_t blocks, cudaStream_t stream);
// Votes for the edges (ids 3 t + k) that the host decided to flip, between the two halves.
void launch_vote_edges(FlipBatch* batch, DeviceSpan<const int32_t> edges, cudaStream_t stream);
// The second half: the flips, the links, the votes reset and the next round's list.
void launch_flips(FlipBatch* batch, int64_t blocks, cudaStream_t stream);

// A repair's rounds in one cooperative launch (after its first, which tests every edge with a
// full grid of its own): rounds until one finds no candidate, or rounds_per_launch of them, the
// grid waiting at a barrier where the kernels above end. A cascade's lists hold a few thousand
// triangles, so a round is bound by its chain of dependent loads more than by its blocks: one
// block per SM did best (G5's flips at 1M nodes on an H200: 167 ms, 195-203 with 2-8 blocks per
// SM, 180 through a CUDA graph of the kernels). Out of graphs with conditional nodes, the rounds
// are also where compute-sanitizer's memcheck can follow them (bench/RESULTS.md).
constexpr int kFlipLoopBlocksPerSm = 1;
// The loop's grid on `device`: kFlipLoopBlocksPerSm blocks per SM, or 0 where the device cannot
// launch cooperatively (then the caller launches the rounds one by one).
int64_t flip_loop_blocks(int device);
void launch_flip_loop(FlipBatch* batch, int64_t blocks, cudaStream_t stream);
// A cascade's tail, once a round's list holds at most this many triangles (FlipBatch::tail_items),
// runs in block 0 of the loop alone, two triangles a thread, with block barriers in place of the
// grid's: at 1M nodes on an H200 it took 16-29% off the graded requests' retriangulations
// (bench/RESULTS.md, 2026-11-28).
constexpr int32_t kFlipTailItems = 2 * kBlock;

// A small repair's rounds (up to kOneBlockRows triangles, launch.h), its first included, in one
// block with block barriers, until one finds no candidate or rounds_per_launch of them: one launch
// on one SM where the first round's kernels and the loop took six launches and, for the loop,
// every SM (many small jobs share the device).
void launch_flip_rounds_in_one_block(FlipBatch* batch, cudaStream_t stream);
// A small repair whole, in one launch of one block: launch_begin_flips, launch_check_orientation
// (launch.h) with `check`'s views (alive: views.walls) and the rounds above; then, where the
// rounds settled with no fatal triangle and nothing left to the host, the removal of the dropped
// triangles (keep_triangles.h). *live is then the triangles' count, for a centroid filter and
// bars launched behind it (launch.h), so that the host reads the counters and the totals once.
// Where the rounds did not settle, the triangles stay as they are and the host goes on from the
// counters; the filter and the bars behind it then go for nothing.
struct OrientationViews {
  DeviceSpan<const uint8_t> keep, on_boundary;
  DeviceSpan<uint8_t> alive;
};
struct OneBlockRepair {
  OrientationViews check;
  DeviceSpan<int32_t> position;        // #M: the removal's scan
  DeviceSpan<Tri> tris_out, nbrs_out;  // #M: the kept triangles before they are copied back
  int64_t* live;
};
void launch_repair_and_keep_in_one_block(const FlipBatch& views, FlipBatch* batch,
                                         const OneBlockRepair& r, cudaStream_t stream);

}  // namespace meshd::gpu
