// A compaction of a linked triangulation: one kept triangle's move, shared by its kernel
// (topology.cu) and the one-block forms (keep_triangles.cu, flip_round.cu): to position[t], the
// exclusive scan of `alive`, with its links renumbered (-1 where the neighbour went); and the whole
// compaction in one block.
#pragma once

#include "kernels/launch.h"
#include "kernels/one_block.cuh"

namespace meshd::gpu {

__device__ inline void compact_triangle(int64_t t, DeviceSpan<const Tri> tris,
                                        DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> alive,
                                        DeviceSpan<const int32_t> position,
                                        DeviceSpan<Tri> tris_out, DeviceSpan<Tri> nbrs_out) {
  Tri n;
  for (int k = 0; k < 3; ++k) {
    const int32_t u = nbrs[t].v[k];
    n.v[k] = (u < 0 || !alive[u]) ? -1 : position[u];
  }
  tris_out[position[t]] = tris[t];
  nbrs_out[position[t]] = n;
}

// Every thread of one block: the triangles with alive[t] (up to kOneBlockRows) moved to the front
// of tris and nbrs, in order, through tris_out and nbrs_out. Returns how many, to every thread.
__device__ inline int32_t compact_in_block(DeviceSpan<const uint8_t> alive, DeviceSpan<Tri> tris,
                                           DeviceSpan<Tri> nbrs, DeviceSpan<int32_t> position,
                                           DeviceSpan<Tri> tris_out, DeviceSpan<Tri> nbrs_out) {
  __shared__ StripeScanStorage scan;
  const int64_t m = tris.size;
  int32_t at[kOneBlockItems];
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j) at[j] = stripe_row(j) < m ? alive[stripe_row(j)] : 0;
  const int32_t kept = scan_stripes(at, scan);
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    if (stripe_row(j) < m) position[stripe_row(j)] = at[j];
  __syncthreads();
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    if (stripe_row(j) < m && alive[stripe_row(j)])
      compact_triangle(stripe_row(j), tris, nbrs, alive, position, tris_out, nbrs_out);
  __syncthreads();
  for (int64_t i = threadIdx.x; i < kept; i += kOneBlockThreads) {
    tris[i] = tris_out[i];
    nbrs[i] = nbrs_out[i];
  }
  return kept;
}

}  // namespace meshd::gpu
