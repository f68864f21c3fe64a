// complete_gaps.h: the gaps' boundary on the device, their triangulation on the host.
#include <array>
#include <utility>
#include <vector>

#include "core/delaunay/complete_triangulation.h"
#include "kernels/complete_gaps.h"
#include "kernels/cuda_check.h"
#include "kernels/keep_triangles.h"
#include "core/delaunay/filtered_predicates.cuh"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

// in_mesh[v]: v is a corner of some triangle; on_gap[v]: of an open edge; open[3 t + k]: the
// edge opposite corner k of triangle t has no neighbour.
__global__ void mark_open_edges(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                                DeviceSpan<uint8_t> in_mesh, DeviceSpan<uint8_t> on_gap,
                                DeviceSpan<uint8_t> open) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri tri = tris[t];
  for (int k = 0; k < 3; ++k) {
    in_mesh[tri.v[k]] = 1;
    const bool is_open = nbrs[t].v[k] < 0;
    open[3 * t + k] = is_open;
    if (is_open) on_gap[tri.v[(k + 1) % 3]] = on_gap[tri.v[(k + 2) % 3]] = 1;
  }
}

__global__ void flag_gap_points(DeviceSpan<const uint8_t> in_mesh, DeviceSpan<const uint8_t> on_gap,
                                int64_t always_gap, DeviceSpan<uint8_t> flag) {
  const int64_t v = thread_index();
  if (v >= flag.size) return;
  flag[v] = v < always_gap || !in_mesh[v] || on_gap[v];
}

__global__ void gather_gap_points(DeviceSpan<const Vec2> p, DeviceSpan<const uint8_t> flag,
                                  DeviceSpan<const int32_t> position, DeviceSpan<int32_t> points,
                                  DeviceSpan<Vec2> positions) {
  const int64_t v = thread_index();
  if (v >= flag.size || !flag[v]) return;
  points[position[v]] = static_cast<int32_t>(v);
  positions[position[v]] = p[v];
}

// walls[2 i], walls[2 i + 1]: the i-th open edge, from -> to with its triangle on the left.
__global__ void gather_walls(DeviceSpan<const Tri> tris, DeviceSpan<const uint8_t> open,
                             DeviceSpan<const int32_t> position, DeviceSpan<int32_t> walls,
                             DeviceSpan<int32_t> uses) {
  const int64_t e = thread_index();
  if (e >= open.size || !open[e]) return;
  const Tri tri = tris[e / 3];
  const int k = static_cast<int>(e % 3);
  const int32_t i = position[e];
  walls[2 * i] = tri.v[(k + 1) % 3];
  walls[2 * i + 1] = tri.v[(k + 2) % 3];
  uses[i] = static_cast<int32_t>(e);
}

// links[2 i] = a wall's use 3 t + k, links[2 i + 1] = the gap triangle across it.
__global__ void link_walls(DeviceSpan<const int32_t> links, DeviceSpan<Tri> nbrs) {
  const int64_t i = thread_index();
  if (2 * i >= links.size) return;
  const int32_t use = links[2 * i];
  nbrs[use / 3].v[use % 3] = links[2 * i + 1];
}

__global__ void mark_folds(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                           DeviceSpan<uint8_t> in_fold, int32_t* folds) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri tri = tris[t];
  if (orientation_filtered(p[tri.v[0]], p[tri.v[1]], p[tri.v[2]]) > 0) return;
  in_fold[tri.v[0]] = in_fold[tri.v[1]] = in_fold[tri.v[2]] = 1;
  atomicAdd(folds, 1);
}

// A triangle that still turns the right way can overlap a fold, but only next to it.
__global__ void off_folds(DeviceSpan<const Tri> tris, DeviceSpan<const uint8_t> in_fold,
                          DeviceSpan<uint8_t> kept) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri tri = tris[t];
  kept[t] = !(in_fold[tri.v[0]] || in_fold[tri.v[1]] || in_fold[tri.v[2]]);
}

__global__ void closed_triangles(DeviceSpan<const Tri> nbrs, DeviceSpan<uint8_t> closed) {
  const int64_t t = thread_index();
  if (t >= nbrs.size) return;
  closed[t] = nbrs[t].v[0] >= 0 && nbrs[t].v[1] >= 0 && nbrs[t].v[2] >= 0;
}

template <typename T, typename Host>
void download_as(const DeviceBuffer<T>& from, std::vector<Host>& to, cudaStream_t stream) {
  static_assert(sizeof(Host) % sizeof(T) == 0);
  to.resize(from.size() * sizeof(T) / sizeof(Host));
  if (!to.empty())
    MESHD_CUDA_CHECK(cudaMemcpyAsync(to.data(), from.data(), from.size() * sizeof(T),
                                     cudaMemcpyDeviceToHost, stream));
}

// What bounds the gaps of tris (complete_triangulation.h's GapBoundary), found on the device.
GapBoundary gap_boundary(DeviceSpan<const Vec2> p, int64_t nfix, const DeviceBuffer<Tri>& tris,
                         const DeviceBuffer<Tri>& nbrs, GapScratch& s, DeviceBuffer<uint8_t>& temp,
                         cudaStream_t stream) {
  const int64_t n = p.size, m = static_cast<int64_t>(tris.size());
  s.in_mesh.resize(n);
  s.on_gap.resize(n);
  s.flag.resize(n);
  s.position.resize(n);
  s.open.resize(3 * m);
  s.open_position.resize(3 * m);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.in_mesh.data(), 0, n, stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.on_gap.data(), 0, n, stream));
  if (m > 0) {
    mark_open_edges<<<blocks_for(m), kBlock, 0, stream>>>(
        tris.span(), nbrs.span(), s.in_mesh.span(), s.on_gap.span(), s.open.span());
    MESHD_CHECK_LAUNCH("mark_open_edges");
  }
  flag_gap_points<<<blocks_for(n), kBlock, 0, stream>>>(s.in_mesh.span(), s.on_gap.span(), nfix,
                                                        s.flag.span());
  MESHD_CHECK_LAUNCH("flag_gap_points");
  exclusive_scan(s.flag.data(), s.position.data(), n, temp, stream);
  const int64_t gap_points = scan_total(s.position.data(), s.flag.data(), n, stream);
  s.points.resize(gap_points);
  s.positions.resize(gap_points);
  gather_gap_points<<<blocks_for(n), kBlock, 0, stream>>>(p, s.flag.span(), s.position.span(),
                                                          s.points.span(), s.positions.span());
  MESHD_CHECK_LAUNCH("gather_gap_points");
  int64_t walls = 0;
  if (m > 0) {
    exclusive_scan(s.open.data(), s.open_position.data(), 3 * m, temp, stream);
    walls = scan_total(s.open_position.data(), s.open.data(), 3 * m, stream);
  }
  s.walls.resize(2 * walls);
  s.uses.resize(walls);
  if (m > 0) {
    gather_walls<<<blocks_for(3 * m), kBlock, 0, stream>>>(
        tris.span(), s.open.span(), s.open_position.span(), s.walls.span(), s.uses.span());
    MESHD_CHECK_LAUNCH("gather_walls");
  }
  GapBoundary b;
  std::vector<int32_t> uses;
  download_as(s.points, b.points, stream);
  download_as(s.positions, b.positions, stream);
  download_as(s.walls, b.walls, stream);
  download_as(s.uses, uses, stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  b.wall_uses.assign(uses.begin(), uses.end());
  return b;
}

// Appends fill's triangles after tris' and links the walls to them.
void append_fill(const GapFill& fill, DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs,
                 GapScratch& s, cudaStream_t stream) {
  static_assert(sizeof(Tri) == sizeof(std::array<int32_t, 3>));
  const size_t m = tris.size(), added = fill.triangles.size();
  auto append = [&](DeviceBuffer<Tri>& to, DeviceBuffer<Tri>& spare,
                    const std::vector<std::array<int32_t, 3>>& more) {
    spare.assign(to, stream);
    to.resize(m + added);  // a growth loses the contents: copied back from spare
    to.assign(spare, stream);
    to.resize(m + added);
    if (added > 0)
      MESHD_CUDA_CHECK(cudaMemcpyAsync(to.data() + m, more.data(), added * sizeof(Tri),
                                       cudaMemcpyHostToDevice, stream));
  };
  append(tris, s.tris, fill.triangles);
  append(nbrs, s.nbrs, fill.neighbors);
  std::vector<int32_t> links;
  links.reserve(2 * fill.wall_links.size());
  for (const auto& [use, gap] : fill.wall_links) {
    links.push_back(static_cast<int32_t>(use));
    links.push_back(gap);
  }
  s.links.upload(links.data(), links.size(), stream);
  const auto count = static_cast<int64_t>(fill.wall_links.size());
  if (count > 0) {
    link_walls<<<blocks_for(count), kBlock, 0, stream>>>(s.links.span(), nbrs.span());
    MESHD_CHECK_LAUNCH("link_walls");
  }
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));  // the uploads read host vectors
}

// Drops the triangles with an open edge (complete_triangulation's erosion).
void erode(DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs, GapScratch& s,
           DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  const auto m = static_cast<int64_t>(tris.size());
  if (m == 0) return;
  s.flag.resize(m);
  closed_triangles<<<blocks_for(m), kBlock, 0, stream>>>(nbrs.span(), s.flag.span());
  MESHD_CHECK_LAUNCH("closed_triangles");
  keep_triangles(s.flag.span(), tris, nbrs, {s.position, s.tris, s.nbrs}, temp, stream);
}

}  // namespace

bool cut_folds(DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris, DeviceBuffer<Tri>& nbrs,
               GapScratch& s, DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  const auto m = static_cast<int64_t>(tris.size());
  if (m == 0) return false;
  s.in_fold.resize(p.size);
  s.folds.resize(1);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.in_fold.data(), 0, p.size, stream));
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.folds.data(), 0, sizeof(int32_t), stream));
  mark_folds<<<blocks_for(m), kBlock, 0, stream>>>(p, tris.span(), s.in_fold.span(),
                                                   s.folds.data());
  MESHD_CHECK_LAUNCH("mark_folds");
  int32_t folds = 0;
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(&folds, s.folds.data(), sizeof(int32_t), cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  if (folds == 0) return false;
  s.flag.resize(m);
  off_folds<<<blocks_for(m), kBlock, 0, stream>>>(tris.span(), s.in_fold.span(), s.flag.span());
  MESHD_CHECK_LAUNCH("off_folds");
  keep_triangles(s.flag.span(), tris, nbrs, {s.position, s.tris, s.nbrs}, temp, stream);
  return true;
}

bool complete_gaps(DeviceSpan<const Vec2> p, int64_t nfix, DeviceBuffer<Tri>& tris,
                   DeviceBuffer<Tri>& nbrs, GapScratch& s, DeviceBuffer<uint8_t>& temp,
                   cudaStream_t stream) {
  for (int erosions = 0;; ++erosions) {
    GapFill fill;
    if (fill_gaps(gap_boundary(p, nfix, tris, nbrs, s, temp, stream), p.size,
                  static_cast<int64_t>(tris.size()), fill)) {
      append_fill(fill, tris, nbrs, s, stream);
      return true;
    }
    if (erosions == kMaxCompletionErosions) return false;
    erode(tris, nbrs, s, temp, stream);
  }
}

}  // namespace meshd::gpu
