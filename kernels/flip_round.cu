// flip_round.h: grid-stride phases over a round's lists, whose lengths live on the device; each
// phase is a kernel of its own, or a stretch of the cooperative loop between two grid barriers,
// or of one block's loop between two block barriers (the loop's tail, a small repair).
#include <cooperative_groups.h>

#include <algorithm>
#include <cstddef>

#include "core/delaunay/filtered_predicates.cuh"
#include "kernels/cooperative_launch.h"
#include "kernels/cuda_check.h"
#include "kernels/flip_round.h"
#include "kernels/one_block.cuh"
#include "kernels/orientation_check.cuh"
#include "kernels/thread_index.cuh"
#include "kernels/triangle_compaction.cuh"

namespace meshd::gpu {
namespace {

// The threads that share a phase's items: the whole grid, or in the loop's tail one block.
struct Lanes {
  int64_t first, step;
};
__device__ inline Lanes grid_lanes() {
  return {thread_index(), static_cast<int64_t>(gridDim.x) * blockDim.x};
}
__device__ inline Lanes block_lanes() { return {threadIdx.x, blockDim.x}; }

// Appends t to `list` unless it is there already (its stamp says so).
__device__ inline void push(int32_t t, int32_t stamp, int32_t* stamps, int32_t* list,
                            int32_t* length) {
  if (t < 0 || atomicExch(&stamps[t], stamp) == stamp) return;
  list[atomicAdd(length, 1)] = t;
}

// Round r reads work list r % 2 and writes the other, for round r + 1.
struct Slots {
  int in, out;
};
__device__ inline Slots slots_of(const FlipBatch& b) {
  const int in = b.round & 1;
  return {in, in ^ 1};
}
__device__ inline void push_next(const FlipBatch& b, Slots s, int32_t t) {
  push(t, b.round + 1, b.work_stamp[s.out], b.work[s.out], &b.counters->queued[s.out]);
}

// force_full: a round the host drives. One thread.
__device__ void open_round_body(FlipBatch* b, bool force_full) {
  TopologyCounters* c = b->counters;
  if (force_full) {
    c->checked = 0;
    c->settled = 0;
    b->full = 1;
  }
  if (c->settled) return;
  // The repair's orientation check found a triangle turned over that it cannot leave as a wall:
  // its caller rebuilds (or drops, then repairs again).
  if (c->fatal > 0 || (c->dropped > 0 && b->walls.size == 0)) {
    c->settled = 1;
    return;
  }
  if (c->checked && c->candidates == 0) {
    c->settled = 1;
    return;
  }
  c->candidates = 0;
  c->undecided = 0;
  c->checked = 1;
  c->voted = 0;
  ++b->round;
  b->round_full = b->full;
  b->full = 0;
  c->queued[slots_of(*b).out] = 0;
}
__global__ void open_round(FlipBatch* b, bool force_full) { open_round_body(b, force_full); }

__device__ void test_edges_body(const FlipBatch& b, Lanes lanes) {
  TopologyCounters* c = b.counters;
  if (c->settled) return;
  const Slots s = slots_of(b);
  const int64_t n = b.round_full ? b.tris.size : c->queued[s.in];
  const int32_t* in = b.work[s.in];
  const int32_t* in_stamp = b.work_stamp[s.in];
  for (int64_t i = lanes.first; i < n; i += lanes.step) {
    const auto t = static_cast<int32_t>(b.round_full ? i : in[i]);
    const bool walled = b.walls.size > 0;
    if (walled && !b.walls[t]) continue;
    const Tri tri = b.tris[t], nbr = b.nbrs[t];
    for (int k = 0; k < 3; ++k) {
      const int32_t u = nbr.v[k];
      if (u < 0 || (walled && !b.walls[u])) continue;
      // Each edge once: from its lower triangle where both are on the list.
      if (u < t && (b.round_full || in_stamp[u] == b.round)) continue;
      const int32_t d = b.tris[u].v[slot_of(b.nbrs[u], t)];
      const int sign = in_circle_filtered(b.p[tri.v[k]], b.p[tri.v[(k + 1) % 3]],
                                          b.p[tri.v[(k + 2) % 3]], b.p[d]);
      const int32_t id = t * 3 + k;
      if (sign > 0) {
        atomicMin(&b.vote[t], id);
        atomicMin(&b.vote[u], id);
        atomicAdd(&c->candidates, 1);
        push(t, b.round, b.voted_stamp, b.voted, &c->voted);
        push(u, b.round, b.voted_stamp, b.voted, &c->voted);
      } else if (sign == 0) {
        const int32_t at = atomicAdd(&c->undecided, 1);
        if (at < b.undecided.size) b.undecided[at] = id;
        push_next(b, s, t);
        push_next(b, s, u);
      }
    }
  }
}
__global__ void test_edges(const FlipBatch* b) { test_edges_body(*b, grid_lanes()); }

__global__ void vote_edges(const FlipBatch* bp, DeviceSpan<const int32_t> edges) {
  const FlipBatch& b = *bp;
  const int64_t i = thread_index();
  if (i >= edges.size) return;
  const int32_t id = edges[i], t = id / 3, u = b.nbrs[t].v[id % 3];
  atomicMin(&b.vote[t], id);
  atomicMin(&b.vote[u], id);
  push(t, b.round, b.voted_stamp, b.voted, &b.counters->voted);
  push(u, b.round, b.voted_stamp, b.voted, &b.counters->voted);
}

// The flip of edge bc between t = [a, b, c] and u = [d, c, b] into t' = [a, b, d], u' = [a, d, c];
// the outer neighbours keep their old ids here and are re-linked by relink.
__device__ void flip_body(const FlipBatch& b, Lanes lanes) {
  TopologyCounters* c = b.counters;
  if (c->settled) return;
  const Slots s = slots_of(b);
  const int64_t n = c->voted;
  for (int64_t i = lanes.first; i < n; i += lanes.step) {
    const int32_t t = b.voted[i];
    for (int k = 0; k < 3; ++k) {
      const int32_t id = t * 3 + k;
      if (b.vote[t] != id) continue;
      const int32_t u = b.nbrs[t].v[k];
      if (u <= t || b.vote[u] != id) continue;
      const int j = slot_of(b.nbrs[u], t);
      const Tri T = b.tris[t], U = b.tris[u], NT = b.nbrs[t], NU = b.nbrs[u];
      const int32_t va = T.v[k], vb = T.v[(k + 1) % 3], vc = T.v[(k + 2) % 3], vd = U.v[j];
      const int32_t n_ab = NT.v[(k + 2) % 3], n_ca = NT.v[(k + 1) % 3];
      const int32_t n_bd = NU.v[(j + 1) % 3], n_dc = NU.v[(j + 2) % 3];
      b.tris[t] = Tri{{va, vb, vd}};
      b.nbrs[t] = Tri{{n_bd, u, n_ab}};
      b.tris[u] = Tri{{va, vd, vc}};
      b.nbrs[u] = Tri{{n_dc, n_ca, t}};
      b.flipped_round[t] = b.flipped_round[u] = b.round;
      b.partner[t] = u;
      b.partner[u] = t;
      atomicAdd(&c->flips, 1);
      // The next round tests the edges of both and of their outer neighbours.
      const int32_t around[6] = {t, u, n_ab, n_ca, n_bd, n_dc};
      for (const int32_t x : around) push_next(b, s, x);
      break;
    }
  }
}
__global__ void flip(const FlipBatch* b) { flip_body(*b, grid_lanes()); }

__device__ inline bool has_edge(const Tri& t, int32_t e0, int32_t e1) {
  bool h0 = false, h1 = false;
  for (int k = 0; k < 3; ++k) {
    h0 |= t.v[k] == e0;
    h1 |= t.v[k] == e1;
  }
  return h0 && h1;
}

__device__ void relink_body(const FlipBatch& b, Lanes lanes) {
  const TopologyCounters* c = b.counters;
  if (c->settled) return;
  const int64_t n = c->voted;
  for (int64_t i = lanes.first; i < n; i += lanes.step) {
    const int32_t x = b.voted[i];
    if (b.flipped_round[x] != b.round) continue;
    const Tri tri = b.tris[x];
    for (int k = 0; k < 3; ++k) {
      const int32_t y = b.nbrs[x].v[k];
      if (y < 0) continue;
      const int32_t e0 = tri.v[(k + 1) % 3], e1 = tri.v[(k + 2) % 3];
      if (b.flipped_round[y] == b.round) {
        // y flipped too: the edge now belongs to y or to y's partner.
        b.nbrs[x].v[k] = has_edge(b.tris[y], e0, e1) ? y : b.partner[y];
      } else {
        // y did not flip: only x's thread writes y's slot for this edge.
        const Tri ty = b.tris[y];
        for (int v = 0; v < 3; ++v)
          if (ty.v[v] != e0 && ty.v[v] != e1) b.nbrs[y].v[v] = x;
      }
    }
  }
}
__global__ void relink(const FlipBatch* b) { relink_body(*b, grid_lanes()); }

// Whether a loop on the device runs another round: the round found candidates, within
// rounds_per_launch rounds of the launch. One thread, before the next round opens.
__device__ bool another_round(FlipBatch& b) {
  const TopologyCounters* c = b.counters;
  const bool again = !c->settled && c->candidates > 0 && ++b.rounds < b.rounds_per_launch;
  if (!again) b.rounds = 0;
  return again;
}

// The voted triangles' votes go back, and those that did not flip test again next round.
__device__ void close_round_body(const FlipBatch& b, Lanes lanes) {
  const TopologyCounters* c = b.counters;
  if (c->settled) return;
  const Slots s = slots_of(b);
  const int64_t n = c->voted;
  for (int64_t i = lanes.first; i < n; i += lanes.step) {
    const int32_t t = b.voted[i];
    b.vote[t] = 0x7f7f7f7f;
    push_next(b, s, t);
  }
}
__global__ void close_round(const FlipBatch* b) { close_round_body(*b, grid_lanes()); }

// The triangles the current round tests; the next round's list, once this round has closed.
__device__ inline int64_t round_work(const FlipBatch& b) {
  return b.round_full ? b.tris.size : b.counters->queued[slots_of(b).in];
}
__device__ inline int64_t next_round_work(const FlipBatch& b) {
  return b.counters->queued[slots_of(b).out];
}

// One round's phases after its opening; `barrier` stands where the kernels above end.
template <class Barrier>
__device__ void round_phases(FlipBatch& b, Lanes lanes, bool leader, Barrier barrier) {
  test_edges_body(b, lanes);
  barrier();
  flip_body(b, lanes);
  barrier();
  relink_body(b, lanes);
  barrier();
  // another_round reads what close_round_body leaves alone, and the next round's opening
  // waits for the barrier below: the decision may share the phase.
  if (leader) b.again = another_round(b);
  close_round_body(b, lanes);
  barrier();
}

// The rounds in one cooperative launch: the same phases as the kernels above, a grid barrier
// between two where those have a kernel boundary. A cascade's tail, once a round's list is short
// enough for one block (tail_items), runs in block 0 alone with block barriers, a fraction of a
// grid barrier's cost; should its list grow past kTailGrowth times that, the launch ends and the
// host launches the grid again.
constexpr int64_t kTailGrowth = 4;
__global__ void flip_loop(FlipBatch* bp) {
  namespace cg = cooperative_groups;
  const cg::grid_group grid = cg::this_grid();
  FlipBatch& b = *bp;
  const bool leader = grid.thread_rank() == 0;
  for (;;) {
    // The decision is the leader's, in a field that only the grid's rounds write: a block that
    // reads it late still finds it, however far block 0 has gone on alone.
    if (leader) {
      open_round_body(bp, false);
      b.tail = round_work(b) <= b.tail_items;
    }
    grid.sync();
    if (b.tail) break;
    round_phases(b, grid_lanes(), leader, [&] { grid.sync(); });
    if (!b.again) return;
  }
  if (blockIdx.x != 0) return;
  for (;;) {
    round_phases(b, block_lanes(), leader, [] { __syncthreads(); });
    if (!b.again) return;
    if (next_round_work(b) > kTailGrowth * b.tail_items) {
      // Unopened, the round waits for the next launch, which counts its rounds afresh.
      if (leader) b.rounds = 0;
      return;
    }
    if (leader) open_round_body(bp, false);
    __syncthreads();
  }
}

// A repair's start: the host's views into *batch and the counters at zero (one thread), and
// triangle i's vote open and its stamps forgotten (set below any round).
__device__ void begin_flips_head(const FlipBatch& views, FlipBatch* batch) {
  memcpy(batch, &views, offsetof(FlipBatch, round));  // the rest belongs to the device
  *views.counters = TopologyCounters{};
}
__device__ void begin_flips_of(const FlipBatch& views, int64_t i) {
  constexpr int32_t kForgotten = static_cast<int32_t>(0x80808080);
  views.vote[i] = 0x7f7f7f7f;
  views.work_stamp[0][i] = views.work_stamp[1][i] = views.voted_stamp[i] = kForgotten;
}
__global__ void begin_flips(FlipBatch views, FlipBatch* batch) {
  const int64_t i = thread_index();
  if (i == 0) begin_flips_head(views, batch);
  if (i < views.tris.size) begin_flips_of(views, i);
}

// A small repair's rounds in one block, its first (full) round included: the loop's tail from
// the start, without a grid.
__device__ void rounds_in_block(FlipBatch* bp) {
  FlipBatch& b = *bp;
  const bool leader = threadIdx.x == 0;
  for (;;) {
    if (leader) open_round_body(bp, false);
    __syncthreads();
    round_phases(b, block_lanes(), leader, [] { __syncthreads(); });
    if (!b.again) return;
  }
}
__global__ void __launch_bounds__(kOneBlockThreads) flip_rounds_in_one_block(FlipBatch* bp) {
  rounds_in_block(bp);
}
// What begin_flips, the orientation check and the rounds do one after the other, with block
// barriers between them; then, where the rounds settled with nothing left to the host, what
// keep_triangles does; the live count for the filter and the bars that follow.
__global__ void __launch_bounds__(kOneBlockThreads)
    repair_and_keep_in_one_block(FlipBatch views, FlipBatch* bp, OneBlockRepair r) {
  if (threadIdx.x == 0) begin_flips_head(views, bp);
  for (int64_t i = threadIdx.x; i < views.tris.size; i += blockDim.x) begin_flips_of(views, i);
  __syncthreads();
  for (int64_t t = threadIdx.x; t < views.tris.size; t += blockDim.x)
    check_orientation_of(t, views.p, views.tris, r.check.keep, r.check.on_boundary, r.check.alive,
                         views.counters);
  __syncthreads();
  rounds_in_block(bp);
  __syncthreads();
  const TopologyCounters* c = views.counters;
  int64_t m = views.tris.size;
  const bool settled =
      __ldcg(&c->fatal) == 0 && __ldcg(&c->undecided) == 0 && __ldcg(&c->candidates) == 0;
  if (settled && __ldcg(&c->dropped) > 0) {
    m = compact_in_block(r.check.alive, views.tris, views.nbrs, r.position, r.tris_out, r.nbrs_out);
    // The rounds' record of each triangle's last flip, for the renumbered triangles.
    for (int64_t i = threadIdx.x; i < m; i += kOneBlockThreads) views.flipped_round[i] = -1;
  }
  if (threadIdx.x == 0) *r.live = m;
}

// Both kinds of round open and test alike; a round the host drives opens afresh.
void launch_round_candidates(FlipBatch* batch, int64_t blocks, bool host_driven,
                             cudaStream_t stream) {
  open_round<<<1, 1, 0, stream>>>(batch, host_driven);
  MESHD_CHECK_LAUNCH("open_round");
  test_edges<<<blocks, kBlock, 0, stream>>>(batch);
  MESHD_CHECK_LAUNCH("test_edges");
}

}  // namespace

void size_flip_lists(FlipLists& lists, int64_t m) {
  for (DeviceBuffer<int32_t>* b : {&lists.work[0], &lists.work[1], &lists.work_stamp[0],
                                   &lists.work_stamp[1], &lists.voted, &lists.voted_stamp})
    b->resize(m);
}

void launch_begin_flips(const FlipBatch& views, FlipBatch* batch, cudaStream_t stream) {
  begin_flips<<<blocks_for(std::max<int64_t>(views.tris.size, 1)), kBlock, 0, stream>>>(views,
                                                                                        batch);
  MESHD_CHECK_LAUNCH("begin_flips");
}

void launch_flip_candidates(FlipBatch* batch, int64_t blocks, cudaStream_t stream) {
  launch_round_candidates(batch, blocks, false, stream);
}

void launch_full_flip_candidates(FlipBatch* batch, int64_t blocks, cudaStream_t stream) {
  launch_round_candidates(batch, blocks, true, stream);
}

void launch_vote_edges(FlipBatch* batch, DeviceSpan<const int32_t> edges, cudaStream_t stream) {
  if (edges.size == 0) return;
  vote_edges<<<blocks_for(edges.size), kBlock, 0, stream>>>(batch, edges);
  MESHD_CHECK_LAUNCH("vote_edges");
}

int64_t flip_loop_blocks(int device) {
  return cooperative_blocks(flip_loop, kBlock, device, kFlipLoopBlocksPerSm);
}

void launch_flip_loop(FlipBatch* batch, int64_t blocks, cudaStream_t stream) {
  launch_cooperative(flip_loop, blocks, kBlock, batch, stream, "flip_loop");
}

void launch_flip_rounds_in_one_block(FlipBatch* batch, cudaStream_t stream) {
  flip_rounds_in_one_block<<<1, kOneBlockThreads, 0, stream>>>(batch);
  MESHD_CHECK_LAUNCH("flip_rounds_in_one_block");
}

void launch_repair_and_keep_in_one_block(const FlipBatch& views, FlipBatch* batch,
                                         const OneBlockRepair& r, cudaStream_t stream) {
  repair_and_keep_in_one_block<<<1, kOneBlockThreads, 0, stream>>>(views, batch, r);
  MESHD_CHECK_LAUNCH("repair_and_keep_in_one_block");
}

void launch_flips(FlipBatch* batch, int64_t blocks, cudaStream_t stream) {
  flip<<<blocks, kBlock, 0, stream>>>(batch);
  MESHD_CHECK_LAUNCH("flip");
  relink<<<blocks, kBlock, 0, stream>>>(batch);
  MESHD_CHECK_LAUNCH("relink");
  close_round<<<blocks, kBlock, 0, stream>>>(batch);
  MESHD_CHECK_LAUNCH("close_round");
}

}  // namespace meshd::gpu
