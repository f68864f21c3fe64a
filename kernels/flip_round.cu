// flip_round.h: grid-stride kernels over a round's lists, whose lengths live on the device.
#include <algorithm>

#include "kernels/cuda_check.h"
#include "kernels/flip_round.h"
#include "kernels/predicates.cuh"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

// A round's lists are read with at most this many blocks (their lengths are on the device).
constexpr int64_t kMaxListBlocks = 2048;

__device__ inline int64_t stride() { return static_cast<int64_t>(gridDim.x) * blockDim.x; }

// Appends t to `list` unless it is there already (its stamp says so).
__device__ inline void push(int32_t t, int32_t stamp, int32_t* stamps, int32_t* list,
                            int32_t* length) {
  if (t < 0 || atomicExch(&stamps[t], stamp) == stamp) return;
  list[atomicAdd(length, 1)] = t;
}

// Where round r reads and writes: rounds alternate between the two work lists.
struct Lists {
  const int32_t *in, *in_stamp;
  int32_t *out, *out_stamp, *voted, *voted_stamp;
  int in_slot, out_slot;
};
Lists lists_of(const FlipRound& r) {
  const int in = r.round & 1, out = in ^ 1;
  return {r.lists->work[in].data(),
          r.lists->work_stamp[in].data(),
          r.lists->work[out].data(),
          r.lists->work_stamp[out].data(),
          r.lists->voted.data(),
          r.lists->voted_stamp.data(),
          in,
          out};
}

__global__ void open_round(TopologyCounters* c, int out_slot) {
  if (c->settled) return;
  if (c->checked && c->candidates == 0) {
    c->settled = 1;
    return;
  }
  c->candidates = 0;
  c->undecided = 0;
  c->checked = 1;
  c->voted = 0;
  c->queued[out_slot] = 0;
}

__global__ void test_edges(FlipRound r, Lists l) {
  TopologyCounters* c = r.counters;
  if (c->settled) return;
  const int64_t n = r.full ? r.tris.size : c->queued[l.in_slot];
  const int32_t next = r.round + 1;
  for (int64_t i = thread_index(); i < n; i += stride()) {
    const auto t = static_cast<int32_t>(r.full ? i : l.in[i]);
    const Tri tri = r.tris[t], nbr = r.nbrs[t];
    for (int k = 0; k < 3; ++k) {
      const int32_t u = nbr.v[k];
      if (u < 0) continue;
      // Each edge once: from its lower triangle where both are on the list.
      if (u < t && (r.full || l.in_stamp[u] == r.round)) continue;
      const int32_t d = r.tris[u].v[slot_of(r.nbrs[u], t)];
      const int s = in_circle_filtered(r.p[tri.v[k]], r.p[tri.v[(k + 1) % 3]],
                                       r.p[tri.v[(k + 2) % 3]], r.p[d]);
      const int32_t id = t * 3 + k;
      if (s > 0) {
        atomicMin(&r.vote[t], id);
        atomicMin(&r.vote[u], id);
        atomicAdd(&c->candidates, 1);
        push(t, r.round, l.voted_stamp, l.voted, &c->voted);
        push(u, r.round, l.voted_stamp, l.voted, &c->voted);
      } else if (s == 0) {
        const int32_t at = atomicAdd(&c->undecided, 1);
        if (at < r.undecided.size) r.undecided[at] = id;
        push(t, next, l.out_stamp, l.out, &c->queued[l.out_slot]);
        push(u, next, l.out_stamp, l.out, &c->queued[l.out_slot]);
      }
    }
  }
}

__global__ void vote_edges(FlipRound r, Lists l, DeviceSpan<const int32_t> edges) {
  const int64_t i = thread_index();
  if (i >= edges.size) return;
  const int32_t id = edges[i], t = id / 3, u = r.nbrs[t].v[id % 3];
  atomicMin(&r.vote[t], id);
  atomicMin(&r.vote[u], id);
  push(t, r.round, l.voted_stamp, l.voted, &r.counters->voted);
  push(u, r.round, l.voted_stamp, l.voted, &r.counters->voted);
}

// The flip of edge bc between t = [a, b, c] and u = [d, c, b] into t' = [a, b, d], u' = [a, d, c];
// the outer neighbours keep their old ids here and are re-linked by relink.
__global__ void flip(FlipRound r, Lists l) {
  TopologyCounters* c = r.counters;
  if (c->settled) return;
  const int64_t n = c->voted;
  const int32_t next = r.round + 1;
  for (int64_t i = thread_index(); i < n; i += stride()) {
    const int32_t t = l.voted[i];
    for (int k = 0; k < 3; ++k) {
      const int32_t id = t * 3 + k;
      if (r.vote[t] != id) continue;
      const int32_t u = r.nbrs[t].v[k];
      if (u <= t || r.vote[u] != id) continue;
      const int j = slot_of(r.nbrs[u], t);
      const Tri T = r.tris[t], U = r.tris[u], NT = r.nbrs[t], NU = r.nbrs[u];
      const int32_t a = T.v[k], b = T.v[(k + 1) % 3], cc = T.v[(k + 2) % 3], d = U.v[j];
      const int32_t n_ab = NT.v[(k + 2) % 3], n_ca = NT.v[(k + 1) % 3];
      const int32_t n_bd = NU.v[(j + 1) % 3], n_dc = NU.v[(j + 2) % 3];
      r.tris[t] = Tri{{a, b, d}};
      r.nbrs[t] = Tri{{n_bd, u, n_ab}};
      r.tris[u] = Tri{{a, d, cc}};
      r.nbrs[u] = Tri{{n_dc, n_ca, t}};
      r.flipped_round[t] = r.flipped_round[u] = r.round;
      r.partner[t] = u;
      r.partner[u] = t;
      atomicAdd(&c->flips, 1);
      // The next round tests the edges of both and of their outer neighbours.
      const int32_t around[6] = {t, u, n_ab, n_ca, n_bd, n_dc};
      for (const int32_t x : around) push(x, next, l.out_stamp, l.out, &c->queued[l.out_slot]);
      break;
    }
  }
}

__device__ inline bool has_edge(const Tri& t, int32_t e0, int32_t e1) {
  bool h0 = false, h1 = false;
  for (int k = 0; k < 3; ++k) {
    h0 |= t.v[k] == e0;
    h1 |= t.v[k] == e1;
  }
  return h0 && h1;
}

__global__ void relink(FlipRound r, Lists l) {
  const TopologyCounters* c = r.counters;
  if (c->settled) return;
  const int64_t n = c->voted;
  for (int64_t i = thread_index(); i < n; i += stride()) {
    const int32_t x = l.voted[i];
    if (r.flipped_round[x] != r.round) continue;
    const Tri tri = r.tris[x];
    for (int k = 0; k < 3; ++k) {
      const int32_t y = r.nbrs[x].v[k];
      if (y < 0) continue;
      const int32_t e0 = tri.v[(k + 1) % 3], e1 = tri.v[(k + 2) % 3];
      if (r.flipped_round[y] == r.round) {
        // y flipped too: the edge now belongs to y or to y's partner.
        r.nbrs[x].v[k] = has_edge(r.tris[y], e0, e1) ? y : r.partner[y];
      } else {
        // y did not flip: only x's thread writes y's slot for this edge.
        const Tri ty = r.tris[y];
        for (int s = 0; s < 3; ++s)
          if (ty.v[s] != e0 && ty.v[s] != e1) r.nbrs[y].v[s] = x;
      }
    }
  }
}

// The voted triangles' votes go back, and those that did not flip test again next round.
__global__ void close_round(FlipRound r, Lists l) {
  TopologyCounters* c = r.counters;
  if (c->settled) return;
  const int64_t n = c->voted;
  for (int64_t i = thread_index(); i < n; i += stride()) {
    const int32_t t = l.voted[i];
    r.vote[t] = 0x7f7f7f7f;
    push(t, r.round + 1, l.out_stamp, l.out, &c->queued[l.out_slot]);
  }
}

int64_t list_blocks(const FlipRound& r) {
  return std::max<int64_t>(1, std::min(blocks_for(r.tris.size), kMaxListBlocks));
}

}  // namespace

void reset_flip_lists(FlipLists& lists, int64_t m, cudaStream_t stream) {
  for (DeviceBuffer<int32_t>* b : {&lists.work[0], &lists.work[1], &lists.work_stamp[0],
                                   &lists.work_stamp[1], &lists.voted, &lists.voted_stamp})
    b->resize(m);
  if (m == 0) return;
  for (DeviceBuffer<int32_t>* b : {&lists.work_stamp[0], &lists.work_stamp[1], &lists.voted_stamp})
    MESHD_CUDA_CHECK(cudaMemsetAsync(b->data(), 0x80, m * sizeof(int32_t), stream));  // < 0
}

void launch_flip_candidates(const FlipRound& r, cudaStream_t stream) {
  const Lists l = lists_of(r);
  open_round<<<1, 1, 0, stream>>>(r.counters, l.out_slot);
  MESHD_CHECK_LAUNCH("open_round");
  if (r.tris.size == 0) return;
  test_edges<<<list_blocks(r), kBlock, 0, stream>>>(r, l);
  MESHD_CHECK_LAUNCH("test_edges");
}

void launch_vote_edges(const FlipRound& r, DeviceSpan<const int32_t> edges, cudaStream_t stream) {
  if (edges.size == 0) return;
  vote_edges<<<blocks_for(edges.size), kBlock, 0, stream>>>(r, lists_of(r), edges);
  MESHD_CHECK_LAUNCH("vote_edges");
}

void launch_flips(const FlipRound& r, cudaStream_t stream) {
  if (r.tris.size == 0) return;
  const Lists l = lists_of(r);
  const int64_t blocks = list_blocks(r);
  flip<<<blocks, kBlock, 0, stream>>>(r, l);
  MESHD_CHECK_LAUNCH("flip");
  relink<<<blocks, kBlock, 0, stream>>>(r, l);
  MESHD_CHECK_LAUNCH("relink");
  close_round<<<blocks, kBlock, 0, stream>>>(r, l);
  MESHD_CHECK_LAUNCH("close_round");
}

}  // namespace meshd::gpu
