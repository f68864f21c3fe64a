// Keeping some triangles of a linked triangulation on the device, in order, with their links
// (-1 where the neighbour went): after a node removal, a repair that dropped slivers, a fold cut
// out, an erosion. One routine for all of them.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// Scratch of keep_triangles: the scan of the flags and the kept triangles before they are
// copied back (copied rather than swapped, so that each buffer keeps its capacity: the arena).
struct KeepScratch {
  DeviceBuffer<int32_t>& position;
  DeviceBuffer<Tri>& tris;
  DeviceBuffer<Tri>& nbrs;
};

// Keeps the triangles t of `tris` (#M, with neighbours `nbrs`) with keep[t] (#M). Returns how
// many. A caller that knows how many (`kept`, as a repair does from its counters) spares the
// wait for the count.
int64_t keep_triangles(DeviceSpan<const uint8_t> keep, DeviceBuffer<Tri>& tris,
                       DeviceBuffer<Tri>& nbrs, KeepScratch scratch, DeviceBuffer<uint8_t>& temp,
                       cudaStream_t stream, int64_t kept = -1);

}  // namespace meshd::gpu
