// refine_level.h: a coarse level split over its midpoints and renumbered, on the device.
#include <cub/block/block_reduce.cuh>

#include "core/distmesh/hilbert_curve.cuh"
#include "core/distmesh/refine_rule.cuh"
#include "kernels/cuda_check.h"
#include "kernels/refine_level.h"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

// Edge j of a triangle runs from corner j to corner j + 1; the neighbour across it sits in slot
// j + 2 (mod 3), and in the neighbour's triangle that edge is edge k + 1 for its slot k.
__device__ inline int32_t across(const Tri& nbr, int j) { return nbr.v[(j + 2) % 3]; }

// Edge (a, b) as (low, high) in one key, ordered as the host's sort of index pairs orders them.
__device__ inline uint64_t edge_key(int32_t a, int32_t b, int bits) {
  const auto lo = static_cast<uint64_t>(a < b ? a : b), hi = static_cast<uint64_t>(a < b ? b : a);
  return (lo << bits) | hi;
}

// Each edge of the mesh (a kept triangle on either side) once, from the lower of its triangles or
// its only one; the other half-edges get `none`, which sorts last.
__global__ void mesh_edge_keys(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                               DeviceSpan<const uint8_t> keep, int bits, uint64_t none,
                               DeviceSpan<uint64_t> key, DeviceSpan<int32_t> edge, int32_t* count) {
  const int64_t e = thread_index();
  if (e >= key.size) return;
  const auto t = static_cast<int32_t>(e / 3);
  const int j = static_cast<int>(e % 3);
  const int32_t u = across(nbrs[t], j);
  const bool in_mesh = keep[t] || (u >= 0 && keep[u]);
  edge[e] = static_cast<int32_t>(e);
  if (in_mesh && (u < 0 || t < u)) {
    key[e] = edge_key(tris[t].v[j], tris[t].v[(j + 1) % 3], bits);
    atomicAdd(count, 1);
  } else {
    key[e] = none;
  }
}

// split_point for each mesh edge, in key order; an edge with a kept triangle on one side only
// bounds the mesh.
__global__ void split_edges(RefineRule rule, DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                            DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> keep,
                            DeviceSpan<const int32_t> edge, DeviceSpan<uint8_t> split,
                            DeviceSpan<Vec2> mid) {
  const int64_t i = thread_index();
  if (i >= split.size) return;
  const int32_t e = edge[i], t = e / 3;
  const int j = e % 3;
  const int32_t a = tris[t].v[j], b = tris[t].v[(j + 1) % 3], u = across(nbrs[t], j);
  const bool bounds_mesh = !(keep[t] && u >= 0 && keep[u]);
  Vec2 m;
  split[i] = split_point(rule.fd, rule.fh, rule.h0, rule.deps, p[a < b ? a : b], p[a < b ? b : a],
                         bounds_mesh, m);
  mid[i] = m;
}

// The split edges' midpoints become nodes n + position[i]; both half-edges learn the index.
__global__ void place_midpoints(DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> edge,
                                DeviceSpan<const uint8_t> split, DeviceSpan<const int32_t> position,
                                DeviceSpan<const Vec2> mid, int64_t n, DeviceSpan<Vec2> points,
                                DeviceSpan<int32_t> midpoint) {
  const int64_t i = thread_index();
  if (i >= split.size || !split[i]) return;
  const auto index = static_cast<int32_t>(n + position[i]);
  points[index] = mid[i];
  const int32_t e = edge[i], t = e / 3, u = across(nbrs[t], e % 3);
  midpoint[e] = index;
  if (u >= 0) midpoint[u * 3 + (slot_of(nbrs[u], t) + 1) % 3] = index;
}

__global__ void count_children(DeviceSpan<const int32_t> midpoint, DeviceSpan<int32_t> count) {
  const int64_t t = thread_index();
  if (t >= count.size) return;
  count[t] = 1 + (midpoint[3 * t] >= 0) + (midpoint[3 * t + 1] >= 0) + (midpoint[3 * t + 2] >= 0);
}

// split_triangle for every triangle; each child's edges keyed for linking (edge k opposite
// corner k, as the neighbour slots run).
__global__ void write_children(DeviceSpan<const Vec2> points, DeviceSpan<const Tri> tris,
                               DeviceSpan<const int32_t> midpoint, DeviceSpan<const int32_t> offset,
                               int bits, DeviceSpan<Tri> children, DeviceSpan<uint64_t> key,
                               DeviceSpan<int32_t> edge) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const int32_t m[3] = {midpoint[3 * t], midpoint[3 * t + 1], midpoint[3 * t + 2]};
  int32_t split[4][3];
  const int count = split_triangle(points.data, tris[t].v, m, split);
  for (int i = 0; i < count; ++i) {
    const int32_t c = offset[t] + i;
    for (int k = 0; k < 3; ++k) {
      children[c].v[k] = split[i][k];
      key[3 * c + k] = edge_key(split[i][(k + 1) % 3], split[i][(k + 2) % 3], bits);
      edge[3 * c + k] = 3 * c + k;
    }
  }
}

// With the children's half-edges sorted by edge, the two of an inner edge lie side by side.
__global__ void link_children(DeviceSpan<const uint64_t> key, DeviceSpan<const int32_t> edge,
                              DeviceSpan<Tri> nbrs) {
  const int64_t i = thread_index();
  if (i >= key.size) return;
  int32_t other = -1;
  if (i > 0 && key[i - 1] == key[i]) {
    other = edge[i - 1];
  } else if (i + 1 < key.size && key[i + 1] == key[i]) {
    other = edge[i + 1];
  }
  nbrs[edge[i] / 3].v[edge[i] % 3] = other < 0 ? -1 : other / 3;
}

constexpr int kBoxThreads = 1024;
struct BoxUnion {
  __device__ Box operator()(const Box& a, const Box& b) const {
    return {{fmin(a.min.x, b.min.x), fmin(a.min.y, b.min.y)},
            {fmax(a.max.x, b.max.x), fmax(a.max.y, b.max.y)}};
  }
};

// The bounding box of points[first..], in one block: a few hundred microseconds at most.
__global__ void bounding_box(DeviceSpan<const Vec2> points, int64_t first, Box* box) {
  Box b{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
  for (int64_t i = first + threadIdx.x; i < points.size; i += blockDim.x) {
    const Vec2 q = points[i];
    b = BoxUnion{}(b, Box{q, q});
  }
  using Reduce = cub::BlockReduce<Box, kBoxThreads>;
  __shared__ typename Reduce::TempStorage storage;
  const Box total = Reduce(storage).Reduce(b, BoxUnion{});
  if (threadIdx.x == 0) *box = total;
}

__global__ void curve_keys(DeviceSpan<const Vec2> points, int64_t first, const Box* box,
                           DeviceSpan<uint32_t> key, DeviceSpan<int32_t> node) {
  const int64_t i = thread_index();
  if (i >= key.size) return;
  const HilbertFrame frame = HilbertFrame::over(box->min, box->max);
  key[i] = frame.key(points[first + i]);
  node[i] = static_cast<int32_t>(first + i);
}

// out[first + k] = points[order[k]], the fixed nodes before them as they are.
__global__ void reorder_points(DeviceSpan<const Vec2> points, int64_t first,
                               DeviceSpan<const int32_t> order, DeviceSpan<Vec2> out,
                               DeviceSpan<int32_t> new_index) {
  const int64_t i = thread_index();
  if (i >= points.size) return;
  const auto old = static_cast<int32_t>(i < first ? i : order[i - first]);
  out[i] = points[old];
  new_index[old] = static_cast<int32_t>(i);
}

}  // namespace

int64_t refine_level(const RefineRule& rule, DeviceSpan<const uint8_t> keep, DeviceBuffer<Vec2>& p,
                     DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs, RefineScratch& s,
                     DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  const auto n = static_cast<int64_t>(p.size()), m = static_cast<int64_t>(tris.size());
  if (m == 0) return n;

  // 1. The mesh's edges in the host's order, (low, high).
  int bits = bits_for(n);
  s.edge_key.resize(3 * m);
  s.edge_key_sorted.resize(3 * m);
  s.edge.resize(3 * m);
  s.edge_sorted.resize(3 * m);
  s.counter.resize(1);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.counter.data(), 0, sizeof(int32_t), stream));
  const uint64_t none = ~uint64_t{0} >> (64 - 2 * bits);
  mesh_edge_keys<<<blocks_for(3 * m), kBlock, 0, stream>>>(tris.span(), nbrs.span(), keep, bits,
                                                           none, s.edge_key.span(), s.edge.span(),
                                                           s.counter.data());
  MESHD_CHECK_LAUNCH("mesh_edge_keys");
  sort_pairs(s.edge_key.data(), s.edge_key_sorted.data(), s.edge.data(), s.edge_sorted.data(),
             3 * m, 2 * bits, temp, stream);
  int32_t edges = 0;
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(&edges, s.counter.data(), sizeof(int32_t), cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (edges == 0) return n;

  // 2. Which split, and their midpoints, numbered after the coarse nodes.
  s.split.resize(edges);
  s.mid.resize(edges);
  s.position.resize(edges);
  const DeviceSpan<const int32_t> mesh_edges{s.edge_sorted.data(), edges};
  split_edges<<<blocks_for(edges), kBlock, 0, stream>>>(
      rule, p.span(), tris.span(), nbrs.span(), keep, mesh_edges, s.split.span(), s.mid.span());
  MESHD_CHECK_LAUNCH("split_edges");
  exclusive_scan(s.split.data(), s.position.data(), edges, temp, stream);
  const int64_t total = n + scan_total(s.position.data(), s.split.data(), edges, stream);
  s.points.resize(total);
  MESHD_CUDA_CHECK(cudaMemcpyAsync(s.points.data(), p.data(), n * sizeof(Vec2),
                                   cudaMemcpyDeviceToDevice, stream));
  s.midpoint.resize(3 * m);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.midpoint.data(), 0xff, 3 * m * sizeof(int32_t), stream));
  place_midpoints<<<blocks_for(edges), kBlock, 0, stream>>>(nbrs.span(), mesh_edges, s.split.span(),
                                                            s.position.span(), s.mid.span(), n,
                                                            s.points.span(), s.midpoint.span());
  MESHD_CHECK_LAUNCH("place_midpoints");

  // 3. Every triangle split over its edges' midpoints; the children linked through their edges.
  s.count.resize(m);
  s.offset.resize(m);
  count_children<<<blocks_for(m), kBlock, 0, stream>>>(s.midpoint.span(), s.count.span());
  MESHD_CHECK_LAUNCH("count_children");
  exclusive_scan(s.count.data(), s.offset.data(), m, temp, stream);
  const int64_t children = scan_total(s.offset.data(), s.count.data(), m, stream);
  bits = bits_for(total);
  s.tris.resize(children);
  s.nbrs.resize(children);
  s.edge_key.resize(3 * children);
  s.edge_key_sorted.resize(3 * children);
  s.edge.resize(3 * children);
  s.edge_sorted.resize(3 * children);
  write_children<<<blocks_for(m), kBlock, 0, stream>>>(
      s.points.span(), tris.span(), s.midpoint.span(), s.offset.span(), bits, s.tris.span(),
      s.edge_key.span(), s.edge.span());
  MESHD_CHECK_LAUNCH("write_children");
  sort_pairs(s.edge_key.data(), s.edge_key_sorted.data(), s.edge.data(), s.edge_sorted.data(),
             3 * children, 2 * bits, temp, stream);
  link_children<<<blocks_for(3 * children), kBlock, 0, stream>>>(
      s.edge_key_sorted.span(), s.edge_sorted.span(), s.nbrs.span());
  MESHD_CHECK_LAUNCH("link_children");

  // 4. The free nodes along the Hilbert curve over their bounding box, the triangles renumbered.
  const int64_t nfix = rule.nfix, free = total - nfix;
  p.resize(total);
  if (free < 2) {
    MESHD_CUDA_CHECK(cudaMemcpyAsync(p.data(), s.points.data(), total * sizeof(Vec2),
                                     cudaMemcpyDeviceToDevice, stream));
  } else {
    s.box.resize(1);
    bounding_box<<<1, kBoxThreads, 0, stream>>>(s.points.span(), nfix, s.box.data());
    MESHD_CHECK_LAUNCH("bounding_box");
    s.curve_key.resize(free);
    s.curve_key_sorted.resize(free);
    s.order.resize(free);
    s.curve_order.resize(free);
    curve_keys<<<blocks_for(free), kBlock, 0, stream>>>(s.points.span(), nfix, s.box.data(),
                                                        s.curve_key.span(), s.order.span());
    MESHD_CHECK_LAUNCH("curve_keys");
    sort_pairs(s.curve_key.data(), s.curve_key_sorted.data(), s.order.data(), s.curve_order.data(),
               free, 2 * kHilbertBits, temp, stream);
    s.new_index.resize(total);
    reorder_points<<<blocks_for(total), kBlock, 0, stream>>>(
        s.points.span(), nfix, s.curve_order.span(), p.span(), s.new_index.span());
    MESHD_CHECK_LAUNCH("reorder_points");
    launch_renumber_vertices(s.tris.span(), s.new_index.span(), stream);
  }
  tris.assign(s.tris, stream);
  nbrs.assign(s.nbrs, stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  return total;
}

}  // namespace meshd::gpu
