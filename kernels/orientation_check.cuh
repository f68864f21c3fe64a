// The repair's orientation check for one triangle, shared by its kernel (topology.cu) and the
// one-block repair (flip_round.cu): a triangle turned over (or undecided, since rebuilding is
// always safe) is fatal where it is kept and not a boundary sliver, and dropped otherwise.
#pragma once

#include "core/delaunay/filtered_predicates.cuh"
#include "kernels/launch.h"

namespace meshd::gpu {

__device__ inline void check_orientation_of(int64_t t, DeviceSpan<const Vec2> p,
                                            DeviceSpan<const Tri> tris,
                                            DeviceSpan<const uint8_t> keep,
                                            DeviceSpan<const uint8_t> on_boundary,
                                            DeviceSpan<uint8_t> alive, TopologyCounters* counters) {
  const Tri tri = tris[t];
  const bool ok = orientation_filtered(p[tri.v[0]], p[tri.v[1]], p[tri.v[2]]) > 0;
  alive[t] = 1;
  if (ok) return;
  const bool sliver = on_boundary[tri.v[0]] && on_boundary[tri.v[1]] && on_boundary[tri.v[2]];
  if (keep[t] && !sliver) {
    atomicAdd(&counters->fatal, 1);
  } else {
    alive[t] = 0;
    atomicAdd(&counters->dropped, 1);
  }
}

}  // namespace meshd::gpu
