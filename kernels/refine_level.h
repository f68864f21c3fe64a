// The multilevel loop's refinement (refine.h) on the device: a coarse level's mesh split over
// its edges' midpoints and renumbered along a Hilbert curve (spatial_order.h), with the same
// rules (refine_rule.cuh, hilbert_curve.cuh) and so the same points as on the host. At a million
// nodes the host's edge sort, split, renumbering and completion took most of a second per level.
//
// The host refines the kept triangles and completes the rest of the convex hull with CGAL. The
// device splits every triangle of the coarse triangulation, kept or not, over the kept
// triangles' midpoints: the children triangulate the coarse hull, linked through a sort of their
// edges, with no completion, unless a projected midpoint left the hull (then the caller
// completes the pockets). Either way the flips that follow end at the same Delaunay
// triangulation.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec2.h"
#include "core/geometry/program.h"
#include "core/geometry/size_program.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// The finer level's rules.
struct RefineRule {
  ProgramView fd;
  SizeView fh;
  double h0;     // the finer level's
  double deps;   // absolute step of the projection's gradient
  int64_t nfix;  // fixed nodes, first, kept first
};

// Buffers of refine_level, kept between jobs (the engine's arena).
struct RefineScratch {
  DeviceBuffer<uint64_t> edge_key, edge_key_sorted;
  DeviceBuffer<uint32_t> curve_key, curve_key_sorted;
  DeviceBuffer<int32_t> edge, edge_sorted, position, midpoint, count, offset, counter;
  DeviceBuffer<int32_t> order, curve_order, new_index;
  DeviceBuffer<uint8_t> split;
  DeviceBuffer<Vec2> mid, points;
  DeviceBuffer<Tri> tris, nbrs;
  DeviceBuffer<Box> box;
};

// Refines the mesh of `p` (#N, fixed first): `tris` (#M, counter-clockwise) triangulate its
// convex hull with neighbours `nbrs` (slot k across the edge opposite corner k, -1 on the hull),
// `keep` (#M) flags the mesh's triangles. Replaces p with the refined level's nodes, in Hilbert
// order after the fixed ones, and tris and nbrs with the split triangles and their links. The
// split triangles may hold folds where a boundary midpoint was projected past a neighbour, and
// pockets along the hull where one was projected out of it. Returns the new node count.
int64_t refine_level(const RefineRule& rule, DeviceSpan<const uint8_t> keep, DeviceBuffer<Vec2>& p,
                     DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs, RefineScratch& s,
                     DeviceBuffer<uint8_t>& temp, cudaStream_t stream);

}  // namespace meshd::gpu
