// Topology on the device: the orientation check that decides between repair and rebuild, the
// undecided in-circle tests' points for the host, the centroid filter and the bar list (the flips
// themselves: flip_round.h).
#include "core/delaunay/filtered_predicates.cuh"
#include "core/distmesh/boundary_sliver.cuh"
#include "core/geometry/sdf_eval.cuh"
#include "kernels/bar_rules.cuh"
#include "kernels/centroid_rule.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"
#include "kernels/orientation_check.cuh"
#include "kernels/thread_index.cuh"
#include "kernels/triangle_compaction.cuh"

namespace meshd::gpu {
namespace {

__global__ void check_orientation(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                  DeviceSpan<const uint8_t> keep,
                                  DeviceSpan<const uint8_t> on_boundary, DeviceSpan<uint8_t> alive,
                                  TopologyCounters* counters) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  check_orientation_of(t, p, tris, keep, on_boundary, alive, counters);
}

__global__ void compact_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                                  DeviceSpan<const uint8_t> alive,
                                  DeviceSpan<const int32_t> position, DeviceSpan<Tri> tris_out,
                                  DeviceSpan<Tri> nbrs_out) {
  const int64_t t = thread_index();
  if (t >= tris.size || !alive[t]) return;
  compact_triangle(t, tris, nbrs, alive, position, tris_out, nbrs_out);
}

__global__ void surviving_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const uint8_t> node_kept,
                                    DeviceSpan<uint8_t> alive) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri tri = tris[t];
  alive[t] = node_kept[tri.v[0]] && node_kept[tri.v[1]] && node_kept[tri.v[2]];
}

__global__ void renumber_vertices(DeviceSpan<Tri> tris, DeviceSpan<const int32_t> new_index) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  for (int k = 0; k < 3; ++k) tris[t].v[k] = new_index[tris[t].v[k]];
}

__global__ void gather_in_circle_tests(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                       DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> ids,
                                       DeviceSpan<InCircleTest> tests) {
  const int64_t i = thread_index();
  if (i >= ids.size) return;
  const int32_t t = ids[i] / 3, k = ids[i] % 3, u = nbrs[t].v[k];
  const Tri tri = tris[t];
  const int32_t d = tris[u].v[slot_of(nbrs[u], t)];
  tests[i] = {p[tri.v[k]], p[tri.v[(k + 1) % 3]], p[tri.v[(k + 2) % 3]], p[d]};
}

__global__ void hull_links(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                           DeviceSpan<int32_t> next, TopologyCounters* counters) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  for (int k = 0; k < 3; ++k) {
    if (nbrs[t].v[k] >= 0) continue;
    next[tris[t].v[(k + 1) % 3]] = tris[t].v[(k + 2) % 3];
    atomicAdd(&counters->candidates, 1);
  }
}

__global__ void hull_turns(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                           DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> next,
                           TopologyCounters* counters) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  for (int k = 0; k < 3; ++k) {
    if (nbrs[t].v[k] >= 0) continue;
    // The triangle lies left of its boundary edge a -> b; at b the boundary goes on to c.
    const int32_t a = tris[t].v[(k + 1) % 3], b = tris[t].v[(k + 2) % 3], c = next[b];
    if (orientation_filtered(p[a], p[b], p[c]) < 0) atomicAdd(&counters->fatal, 1);
  }
}

// Rows past *live (null: none) are room for a triangulation that may grow: no triangle there.
__device__ inline bool past_live(int64_t t, const int64_t* live) {
  return live != nullptr && t >= *live;
}

__global__ void centroid_filter(DeviceSpan<const Vec2> p, CentroidFilter filter,
                                DeviceSpan<const Tri> tris, DeviceSpan<uint8_t> keep,
                                const int64_t* live) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  keep[t] = !past_live(t, live) && centroid_kept(filter, p, tris[t]);
}

__global__ void mark_boundary_slivers(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                      DeviceSpan<const uint8_t> keep, ProgramView fd, double geps,
                                      int64_t nfix, DeviceSpan<uint8_t> node_keep) {
  const int64_t t = thread_index();
  if (t >= tris.size || !keep[t]) return;
  const Tri tri = tris[t];
  const Vec2 a = p[tri.v[0]], b = p[tri.v[1]], c = p[tri.v[2]];
  if (!is_sliver(a, b, c)) return;
  if (!(eval_sdf(fd, a) > -geps) || !(eval_sdf(fd, b) > -geps) || !(eval_sdf(fd, c) > -geps))
    return;
  const int32_t v = tri.v[largest_angle_corner(a, b, c)];
  if (v >= nfix) node_keep[v] = 0;
}

__global__ void count_bars(DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> keep,
                           DeviceSpan<int32_t> count, const int64_t* live) {
  const int64_t t = thread_index();
  if (t >= nbrs.size) return;
  if (past_live(t, live)) {
    count[t] = 0;
    return;
  }
  count[t] = bars_of(t, nbrs, keep);
}

__global__ void write_bars(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                           DeviceSpan<const uint8_t> keep, DeviceSpan<const int32_t> position,
                           DeviceSpan<Bar> bars, const int64_t* live) {
  const int64_t t = thread_index();
  if (t >= tris.size || past_live(t, live)) return;
  write_bars_of(t, tris, nbrs, keep, position[t], bars);
}

__global__ void count_bar_ends(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                               DeviceSpan<int32_t> degree) {
  const int64_t b = thread_index();
  if (b >= bars.size || b >= *bar_count) return;
  const Bar bar = bars[b];
  atomicAdd(&degree[bar.a], 1);
  atomicAdd(&degree[bar.b], 1);
}

// Each bar end into its node's row, in whatever order the atomics give; degree counts down to
// zero on the way.
__global__ void place_bar_ends(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                               DeviceSpan<const int32_t> csr_offset, DeviceSpan<int32_t> degree,
                               DeviceSpan<int32_t> csr_entry) {
  const int64_t k = thread_index();
  if (k >= 2 * bars.size || k >= 2 * *bar_count) return;
  const Bar bar = bars[k >> 1];
  const int32_t node = (k & 1) ? bar.b : bar.a;
  const int32_t slot = csr_offset[node] + atomicSub(&degree[node], 1) - 1;
  csr_entry[slot] = static_cast<int32_t>(k);
}

// A node's row sorted, and each entry's far end.
__global__ void order_rows(DeviceSpan<const Bar> bars, DeviceSpan<const int32_t> csr_offset,
                           DeviceSpan<int32_t> csr_entry, DeviceSpan<int32_t> other) {
  const int64_t i = thread_index();
  if (i + 1 >= csr_offset.size) return;
  order_row(bars, csr_offset[i], csr_offset[i + 1], csr_entry, other);
}

}  // namespace

void launch_check_orientation(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                              DeviceSpan<const uint8_t> keep, DeviceSpan<const uint8_t> on_boundary,
                              DeviceSpan<uint8_t> alive, TopologyCounters* counters,
                              cudaStream_t stream) {
  if (tris.size == 0) return;
  check_orientation<<<blocks_for(tris.size), kBlock, 0, stream>>>(p, tris, keep, on_boundary, alive,
                                                                  counters);
  MESHD_CHECK_LAUNCH("check_orientation");
}

void launch_compact_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                              DeviceSpan<const uint8_t> alive, DeviceSpan<const int32_t> position,
                              DeviceSpan<Tri> tris_out, DeviceSpan<Tri> nbrs_out,
                              cudaStream_t stream) {
  if (tris.size == 0) return;
  compact_triangles<<<blocks_for(tris.size), kBlock, 0, stream>>>(tris, nbrs, alive, position,
                                                                  tris_out, nbrs_out);
  MESHD_CHECK_LAUNCH("compact_triangles");
}

void launch_surviving_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const uint8_t> node_kept,
                                DeviceSpan<uint8_t> alive, cudaStream_t stream) {
  if (tris.size == 0) return;
  surviving_triangles<<<blocks_for(tris.size), kBlock, 0, stream>>>(tris, node_kept, alive);
  MESHD_CHECK_LAUNCH("surviving_triangles");
}

void launch_renumber_vertices(DeviceSpan<Tri> tris, DeviceSpan<const int32_t> new_index,
                              cudaStream_t stream) {
  if (tris.size == 0) return;
  renumber_vertices<<<blocks_for(tris.size), kBlock, 0, stream>>>(tris, new_index);
  MESHD_CHECK_LAUNCH("renumber_vertices");
}

void launch_gather_in_circle_tests(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                   DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> ids,
                                   DeviceSpan<InCircleTest> tests, cudaStream_t stream) {
  if (ids.size == 0) return;
  gather_in_circle_tests<<<blocks_for(ids.size), kBlock, 0, stream>>>(p, tris, nbrs, ids, tests);
  MESHD_CHECK_LAUNCH("gather_in_circle_tests");
}

void launch_hull_links(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                       DeviceSpan<int32_t> next, TopologyCounters* counters, cudaStream_t stream) {
  if (tris.size == 0) return;
  hull_links<<<blocks_for(tris.size), kBlock, 0, stream>>>(tris, nbrs, next, counters);
  MESHD_CHECK_LAUNCH("hull_links");
}

void launch_hull_turns(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                       DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> next,
                       TopologyCounters* counters, cudaStream_t stream) {
  if (tris.size == 0) return;
  hull_turns<<<blocks_for(tris.size), kBlock, 0, stream>>>(p, tris, nbrs, next, counters);
  MESHD_CHECK_LAUNCH("hull_turns");
}

void launch_mark_boundary_slivers(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                  DeviceSpan<const uint8_t> keep, ProgramView fd, double geps,
                                  int64_t nfix, DeviceSpan<uint8_t> node_keep,
                                  cudaStream_t stream) {
  if (tris.size == 0) return;
  mark_boundary_slivers<<<blocks_for(tris.size), kBlock, 0, stream>>>(p, tris, keep, fd, geps, nfix,
                                                                      node_keep);
  MESHD_CHECK_LAUNCH("mark_boundary_slivers");
}

void launch_centroid_filter(DeviceSpan<const Vec2> p, DeviceSpan<const float> clearance,
                            const ClearanceRule& clear, DeviceSpan<const Tri> tris, ProgramView fd,
                            bool nested_index, double geps, DeviceSpan<uint8_t> keep,
                            const int64_t* live, cudaStream_t stream) {
  if (tris.size == 0) return;
  centroid_filter<<<blocks_for(tris.size), kBlock, 0, stream>>>(
      p, {clearance, clear, fd, nested_index, geps}, tris, keep, live);
  MESHD_CHECK_LAUNCH("centroid_filter");
}

void launch_count_bars(DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> keep,
                       DeviceSpan<int32_t> count, const int64_t* live, cudaStream_t stream) {
  if (nbrs.size == 0) return;
  count_bars<<<blocks_for(nbrs.size), kBlock, 0, stream>>>(nbrs, keep, count, live);
  MESHD_CHECK_LAUNCH("count_bars");
}

void launch_write_bars(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                       DeviceSpan<const uint8_t> keep, DeviceSpan<const int32_t> position,
                       DeviceSpan<Bar> bars, const int64_t* live, cudaStream_t stream) {
  if (tris.size == 0) return;
  write_bars<<<blocks_for(tris.size), kBlock, 0, stream>>>(tris, nbrs, keep, position, bars, live);
  MESHD_CHECK_LAUNCH("write_bars");
}

void launch_count_bar_ends(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                           DeviceSpan<int32_t> degree, cudaStream_t stream) {
  if (bars.size == 0) return;
  count_bar_ends<<<blocks_for(bars.size), kBlock, 0, stream>>>(bars, bar_count, degree);
  MESHD_CHECK_LAUNCH("count_bar_ends");
}

void launch_fill_csr(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                     DeviceSpan<const int32_t> csr_offset, DeviceSpan<int32_t> degree,
                     DeviceSpan<int32_t> csr_entry, DeviceSpan<int32_t> other,
                     cudaStream_t stream) {
  if (bars.size == 0) return;
  place_bar_ends<<<blocks_for(2 * bars.size), kBlock, 0, stream>>>(bars, bar_count, csr_offset,
                                                                   degree, csr_entry);
  MESHD_CHECK_LAUNCH("place_bar_ends");
  order_rows<<<blocks_for(csr_offset.size), kBlock, 0, stream>>>(bars, csr_offset, csr_entry,
                                                                 other);
  MESHD_CHECK_LAUNCH("order_rows");
}

}  // namespace meshd::gpu
