// complete_triangulation.h for a triangulation kept on the device: what bounds its gaps (the
// walls and the gaps' points, a few thousand at a million nodes) is found on the device and
// sent to the host, CGAL triangulates the gaps there, and their triangles come back and are
// linked in. Downloading a million triangles, completing them on the host and uploading them
// again took half a second; this moves a few hundred kilobytes.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec2.h"
#include "core/delaunay/complete_triangulation.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// Buffers of complete_gaps and cut_folds, kept between jobs (the engine's arena).
struct GapScratch {
  DeviceBuffer<uint8_t> in_mesh, on_gap, in_fold, flag, open;
  DeviceBuffer<int32_t> position, open_position, points, walls, uses, links, folds;
  DeviceBuffer<Vec2> positions;
  DeviceBuffer<Tri> tris, nbrs;
};

// Completes `tris` with neighbours `nbrs` (counter-clockwise, linked, -1 across open edges: a
// triangulation of some of the points p, fixed ones first) into a triangulation of p's convex
// hull, as complete_triangulation does with `always_gap` = nfix: the gaps filled, the triangles
// next to them eroded and the gaps filled again where a check fails. Not Delaunay in general:
// the caller flips it. Returns false, with tris and nbrs eroded kMaxCompletionErosions times,
// when every try failed.
bool complete_gaps(DeviceSpan<const Vec2> p, int64_t nfix, DeviceBuffer<Tri>& tris,
                   DeviceBuffer<Tri>& nbrs, GapScratch& s, DeviceBuffer<uint8_t>& temp,
                   cudaStream_t stream);

// refill_folds.h's cut_folds on the device: drops from `tris` every triangle that shares a node
// with one turned over or flat for p (with the device's filtered predicate, undecided counts as
// flat), unlinking its neighbours. Returns whether there was any.
bool cut_folds(DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs,
               GapScratch& s, DeviceBuffer<uint8_t>& temp, cudaStream_t stream);

}  // namespace meshd::gpu
