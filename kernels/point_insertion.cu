// point_insertion.h: one kernel per step of parallel_insertion.cuh, and the host loop that
// reads a count back after each step.
#include <algorithm>
#include <cfloat>
#include <cstring>

#include "core/common/error.h"
#include "core/delaunay/parallel_insertion.cuh"
#include "kernels/cuda_check.h"
#include "kernels/keep_triangles.h"
#include "kernels/point_insertion.h"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

// A double as an unsigned integer in the same order, so that atomicMin and atomicMax order it.
__device__ inline unsigned long long ordered_bits(double x) {
  const auto bits = static_cast<unsigned long long>(__double_as_longlong(x + 0.0));
  return (bits >> 63) ? ~bits : bits | (1ull << 63);
}
double from_ordered_bits(unsigned long long bits) {
  bits = (bits >> 63) ? bits & ~(1ull << 63) : ~bits;
  double x;
  memcpy(&x, &bits, sizeof x);
  return x;
}

// bounds: min x, min y as ordered bits, then max x, max y.
__global__ void point_bounds(DeviceSpan<const Vec2> p, unsigned long long* bounds) {
  double lo_x = DBL_MAX, lo_y = DBL_MAX, hi_x = -DBL_MAX, hi_y = -DBL_MAX;
  for (int64_t i = thread_index(); i < p.size; i += gridDim.x * static_cast<int64_t>(blockDim.x)) {
    lo_x = fmin(lo_x, p[i].x);
    lo_y = fmin(lo_y, p[i].y);
    hi_x = fmax(hi_x, p[i].x);
    hi_y = fmax(hi_y, p[i].y);
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    lo_x = fmin(lo_x, __shfl_down_sync(0xffffffffu, lo_x, offset));
    lo_y = fmin(lo_y, __shfl_down_sync(0xffffffffu, lo_y, offset));
    hi_x = fmax(hi_x, __shfl_down_sync(0xffffffffu, hi_x, offset));
    hi_y = fmax(hi_y, __shfl_down_sync(0xffffffffu, hi_y, offset));
  }
  if (threadIdx.x % 32 != 0) return;
  atomicMin(&bounds[0], ordered_bits(lo_x));
  atomicMin(&bounds[1], ordered_bits(lo_y));
  atomicMax(&bounds[2], ordered_bits(hi_x));
  atomicMax(&bounds[3], ordered_bits(hi_y));
}

__global__ void start_insertion(InsertionState s) {
  s.tris[0] = Tri{{s.n, s.n + 1, s.n + 2}};
  s.nbrs[0] = Tri{{-1, -1, -1}};
}

__global__ void vote_points(InsertionState s) {
  const int64_t i = thread_index();
  if (i < s.n) vote_for_point(s, static_cast<int32_t>(i));
}

__global__ void flag_winners(InsertionState s, uint8_t* wins) {
  const int64_t i = thread_index();
  if (i < s.n) wins[i] = point_wins(s, static_cast<int32_t>(i));
}

__global__ void insert_winners(InsertionState s, const uint8_t* wins, const int32_t* position,
                               int32_t m, int32_t step) {
  const int64_t i = thread_index();
  if (i < s.n && wins[i]) insert_point(s, static_cast<int32_t>(i), m + 2 * position[i], step);
}

__global__ void relink(InsertionState s, int32_t m, int32_t step) {
  const int64_t x = thread_index();
  if (x < m && s.stamp[x] == step) relink_triangle(s, static_cast<int32_t>(x), step);
}

__global__ void relocate(InsertionState s, int32_t step) {
  const int64_t i = thread_index();
  if (i < s.n) relocate_point(s, static_cast<int32_t>(i), step);
}

__global__ void vote_flips(InsertionState s, int32_t m, int32_t since, int32_t step) {
  const int64_t t = thread_index();
  if (t < m) vote_for_flips(s, static_cast<int32_t>(t), since, step);
}

__global__ void flip_edges(InsertionState s, int32_t m, int32_t step) {
  const int64_t t = thread_index();
  if (t < m) flip_won_edge(s, static_cast<int32_t>(t), step);
}

__global__ void flag_real_triangles(DeviceSpan<const Tri> tris, int32_t n, uint8_t* keep) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri v = tris[t];
  keep[t] = v.v[0] < n && v.v[1] < n && v.v[2] < n;
}

}  // namespace

InsertionCounts insert_points(DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris,
                              DeviceBuffer<Tri>& nbrs, InsertionScratch& s,
                              DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  InsertionCounts counts;
  const auto n = static_cast<int32_t>(p.size);
  const int64_t room = 2 * static_cast<int64_t>(n) + 1;
  if (n == 0) {
    tris.resize(0);
    nbrs.resize(0);
    return counts;
  }
  // The enclosing triangle around the points' box.
  s.bounds.resize(4);
  unsigned long long start[4] = {~0ull, ~0ull, 0ull, 0ull};
  for (int k = 0; k < 4; ++k) (*s.h_bounds.get())[k] = start[k];
  MESHD_CUDA_CHECK(cudaMemcpyAsync(s.bounds.data(), s.h_bounds.get(), sizeof start,
                                   cudaMemcpyHostToDevice, stream));
  point_bounds<<<std::min<int64_t>(blocks_for(n), 1024), kBlock, 0, stream>>>(p, s.bounds.data());
  MESHD_CHECK_LAUNCH("point_bounds");
  MESHD_CUDA_CHECK(cudaMemcpyAsync(s.h_bounds.get(), s.bounds.data(), sizeof start,
                                   cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  const unsigned long long* b = *s.h_bounds.get();
  Vec2 corners[3];
  enclosing_triangle({from_ordered_bits(b[0]), from_ordered_bits(b[1])},
                     {from_ordered_bits(b[2]), from_ordered_bits(b[3])}, corners);

  s.p.resize(n + 3);
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(s.p.data(), p.data, n * sizeof(Vec2), cudaMemcpyDeviceToDevice, stream));
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(s.p.data() + n, corners, sizeof corners, cudaMemcpyHostToDevice, stream));
  tris.resize(room);
  nbrs.resize(room);
  s.vote.resize(room);
  s.family.resize(2 * room);
  s.stamp.resize(room);
  s.loc.resize(n);
  s.edge.resize(n);
  s.flags.resize(std::max<int64_t>(n, room));
  s.position.resize(n);
  s.counters.resize(2);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.family.data(), 0xff, 2 * room * sizeof(int32_t), stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.stamp.data(), 0xff, room * sizeof(int32_t), stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.loc.data(), 0, n * sizeof(int32_t), stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.edge.data(), 0xff, n, stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.counters.data(), 0, 2 * sizeof(int32_t), stream));
  // The corners' copy reads `corners` on the host: done before it goes out of scope.
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));

  const InsertionState st{s.p.data(),           n,
                          tris.data(),          nbrs.data(),
                          s.loc.data(),         s.edge.data(),
                          s.vote.data(),        s.family.data(),
                          s.stamp.data(),       s.counters.data(),
                          s.counters.data() + 1};
  start_insertion<<<1, 1, 0, stream>>>(st);
  MESHD_CHECK_LAUNCH("start_insertion");

  const int64_t point_blocks = blocks_for(n);
  int32_t m = 1, step = 0;
  int32_t* h = *s.h_counters.get();
  // Flip steps over what changed since step `since`, as the host's HostInsertion::flip.
  const auto flip = [&](int32_t since, bool may_wait) {
    int64_t first = -1;
    for (;;) {
      ++step;
      MESHD_CUDA_CHECK(
          cudaMemsetAsync(s.vote.data(), 0xff, m * sizeof(unsigned long long), stream));
      vote_flips<<<blocks_for(m), kBlock, 0, stream>>>(st, m, since, step);
      MESHD_CHECK_LAUNCH("vote_flips");
      MESHD_CUDA_CHECK(cudaMemsetAsync(s.counters.data(), 0, sizeof(int32_t), stream));
      flip_edges<<<blocks_for(m), kBlock, 0, stream>>>(st, m, step);
      MESHD_CHECK_LAUNCH("flip_edges");
      relink<<<blocks_for(m), kBlock, 0, stream>>>(st, m, step);
      MESHD_CHECK_LAUNCH("relink");
      relocate<<<point_blocks, kBlock, 0, stream>>>(st, step);
      MESHD_CHECK_LAUNCH("relocate");
      MESHD_CUDA_CHECK(cudaMemcpyAsync(h, s.counters.data(), 2 * sizeof(int32_t),
                                       cudaMemcpyDeviceToHost, stream));
      MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
      ++counts.flip_steps;
      counts.flips += h[0];
      if (h[1] > 0) throw Error(ErrorCode::kInternal, "", "point insertion lost a point");
      if (h[0] == 0) return -1;
      if (first < 0) {
        first = h[0];
      } else if (may_wait && flips_may_wait(first, h[0])) {
        return since;
      }
    }
  };
  // Until no point is left to win a triangle: every point is in, or found a twin there.
  int32_t since = -1;
  for (;;) {
    ++step;
    if (since < 0) since = step;
    MESHD_CUDA_CHECK(cudaMemsetAsync(s.vote.data(), 0xff, m * sizeof(unsigned long long), stream));
    vote_points<<<point_blocks, kBlock, 0, stream>>>(st);
    MESHD_CHECK_LAUNCH("vote_points");
    flag_winners<<<point_blocks, kBlock, 0, stream>>>(st, s.flags.data());
    MESHD_CHECK_LAUNCH("flag_winners");
    exclusive_scan(s.flags.data(), s.position.data(), n, temp, stream);
    const int64_t won = scan_total(s.position.data(), s.flags.data(), n, stream);
    if (won == 0) break;
    insert_winners<<<point_blocks, kBlock, 0, stream>>>(st, s.flags.data(), s.position.data(), m,
                                                        step);
    MESHD_CHECK_LAUNCH("insert_winners");
    m += 2 * static_cast<int32_t>(won);
    relink<<<blocks_for(m), kBlock, 0, stream>>>(st, m, step);
    MESHD_CHECK_LAUNCH("relink");
    relocate<<<point_blocks, kBlock, 0, stream>>>(st, step);
    MESHD_CHECK_LAUNCH("relocate");
    ++counts.insertion_steps;
    since = flip(since, true);
  }
  if (since >= 0) flip(since, false);
  tris.resize(m);
  nbrs.resize(m);
  flag_real_triangles<<<blocks_for(m), kBlock, 0, stream>>>(tris.span(), n, s.flags.data());
  MESHD_CHECK_LAUNCH("flag_real_triangles");
  keep_triangles({s.flags.data(), m}, tris, nbrs, {s.position, s.tris_tmp, s.nbrs_tmp}, temp,
                 stream);
  return counts;
}

}  // namespace meshd::gpu
