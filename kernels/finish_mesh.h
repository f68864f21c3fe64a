// The finish of a GPU job (engine.h: read_mesh, measure_quality) on the device: the boundary from
// the kept triangles' links, the triangles the worst-element optimisation starts from, whether
// the arrays are tidy, and the quality summary. On the host, at a million nodes, matching edges
// for the boundary, measuring every triangle for the optimisation and again for the summary
// took about 0.15 s of a job's 0.3-0.8 s.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/mesh/quality.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"

namespace meshd::gpu {

// Per-block partials of the quality summary, and its total.
struct QualitySums {
  double sum;
  double q_min;
  double angle_min;  // degrees
  long long histogram[kQualityBins];
};

// Buffers of the finish, kept between jobs (the engine's arena).
struct FinishScratch {
  DeviceBuffer<uint8_t> edge_flag, below_flag, used, on_boundary;
  DeviceBuffer<int32_t> valence;
  DeviceBuffer<int32_t> edge_position, below_position, ids;
  DeviceBuffer<int32_t> counts;  // turned-over triangles, unused points, trapped nodes
  DeviceBuffer<Tri> tris;        // the engine's copy of the result's triangles
  DeviceBuffer<QualitySums> partial;
};

// What the host learns about the kept triangles.
struct MeshFacts {
  std::vector<int32_t> boundary;  // boundary_half_edges's ids (core/mesh/boundary.h)
  std::vector<int32_t> below;     // oriented_radius_ratio < below_quality, increasing
  bool tidy = false;              // every point used, no triangle turning clockwise
  // No node from nfix on, off the boundary, is a corner of exactly three triangles: the finish
  // need not look for trapped nodes (trapped_nodes.h).
  bool none_trapped = false;
};

// tris: the kept triangles (#M, corners in p, #N, the first nfix fixed) and nbrs their links
// (slot k across the edge opposite corner k, -1 where the neighbour is not kept). Waits for the
// stream.
MeshFacts find_mesh_facts(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                          DeviceSpan<const Tri> nbrs, double below_quality, int64_t nfix,
                          FinishScratch& s, DeviceBuffer<uint8_t>& temp, cudaStream_t stream);

// summarize_quality (quality.h) of the triangles `tris` over `p`: the same radius ratios, bins
// and smallest angle; the mean summed in another order. Waits for the stream.
QualityStats measure_quality(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris, FinishScratch& s,
                             cudaStream_t stream);

}  // namespace meshd::gpu
