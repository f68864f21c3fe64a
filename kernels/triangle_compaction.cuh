// One kept triangle's move in a compaction of a linked triangulation, shared by its kernel
// (topology.cu) and the one-block form (keep_triangles.cu): to position[t], the exclusive scan of
// `alive`, with its links renumbered (-1 where the neighbour went).
#pragma once

#include "kernels/launch.h"

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

}  // namespace meshd::gpu
