// initial_triangulation.h on the device: the lattice triangles with three kept corners and no
// fixed point in them, numbered and linked in the host's order, then completed by complete_gaps
// (the host triangulates only the gaps' few thousand points). The same triangles and links as
// the host's, bit for bit; at a million nodes the host's version allocated and filled about
// 90 MB, then uploaded half of it.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec2.h"
#include "core/distmesh/initial_points.cuh"
#include "kernels/complete_gaps.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// Buffers of lattice_triangulation, kept between jobs (the engine's arena).
struct LatticeScratch {
  DeviceBuffer<uint8_t> in_u;
  DeviceBuffer<int32_t> u_position;
};

// kept: #(nx ny) flags of the grid points kept by step 2, kept_position their exclusive scan;
// p: the fixed points (#F, first), then the kept grid points in grid order. Writes the
// triangulation of p's convex hull to tris and nbrs (counter-clockwise; slot k across the edge
// opposite corner k, -1 on the hull). Returns false when the completion failed: the caller then
// triangulates from scratch.
bool lattice_triangulation(const InitialGrid& grid, DeviceSpan<const uint8_t> kept,
                           DeviceSpan<const int32_t> kept_position, int64_t nfix,
                           DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris,
                           DeviceBuffer<Tri>& nbrs, LatticeScratch& s, GapScratch& gaps,
                           DeviceBuffer<uint8_t>& temp, cudaStream_t stream);

}  // namespace meshd::gpu
