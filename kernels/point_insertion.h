// The Delaunay builder on the device: parallel point insertion and flipping
// (core/delaunay/parallel_insertion.cuh), step for step as the host's reference
// (core/delaunay/parallel_insertion.h) runs it. It serves the GPU engine's full triangulations,
// which the engine then completes to the convex hull and repairs with exact predicates.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec2.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"
#include "kernels/pinned_value.h"

namespace meshd::gpu {

// The builder's buffers, kept between jobs (the engine's arena).
struct InsertionScratch {
  DeviceBuffer<Vec2> p;  // the points and the enclosing triangle's corners
  DeviceBuffer<int32_t> loc, family, stamp, position, counters;
  DeviceBuffer<int8_t> edge;
  DeviceBuffer<uint8_t> flags;
  DeviceBuffer<unsigned long long> vote, bounds;
  DeviceBuffer<Tri> tris_tmp, nbrs_tmp;
  PinnedValue<int32_t[2]> h_counters;
  PinnedValue<unsigned long long[4]> h_bounds;
};

struct InsertionCounts {
  int insertion_steps = 0;
  int flip_steps = 0;
  int64_t flips = 0;
};

// Triangulates the points p (distinct) by insertion into `tris` and `nbrs`: the triangles of the
// points alone (the enclosing corners' dropped), counter-clockwise and linked, -1 across open
// edges. Delaunay where the filter was certain; the pockets along the hull that the enclosing
// corners' circles swallowed are missing. The caller completes them (complete_gaps.h) and repairs
// with exact predicates, as insertion_triangulate does on the host.
InsertionCounts insert_points(DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris,
                              DeviceBuffer<Tri>& nbrs, InsertionScratch& s,
                              DeviceBuffer<uint8_t>& temp, cudaStream_t stream);

}  // namespace meshd::gpu
