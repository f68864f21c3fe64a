// finish_mesh.h: flags and scans for the boundary and the triangles to optimise, a deterministic
// reduction for the quality summary.
#include <cub/block/block_reduce.cuh>

#include "core/mesh/min_angle.cuh"
#include "core/mesh/radius_ratio.cuh"
#include "kernels/cuda_check.h"
#include "kernels/finish_mesh.h"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

__global__ void flag_triangle_facts(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                    DeviceSpan<const Tri> nbrs, double below_quality,
                                    DeviceSpan<uint8_t> edge_flag, DeviceSpan<uint8_t> below_flag,
                                    DeviceSpan<uint8_t> used, DeviceSpan<uint8_t> on_boundary,
                                    DeviceSpan<int32_t> valence, int32_t* turned) {
  const int64_t t = thread_index();
  if (t >= tris.size) return;
  const Tri tri = tris[t], nbr = nbrs[t];
  const Vec2 a = p[tri.v[0]], b = p[tri.v[1]], c = p[tri.v[2]];
  below_flag[t] = oriented_radius_ratio(a, b, c) < below_quality;
  if (cross(b - a, c - a) < 0.0) atomicAdd(turned, 1);
  // Half-edge 3 t + k runs from corner k to corner k + 1, across from corner k + 2.
  for (int k = 0; k < 3; ++k) {
    const bool open = nbr.v[(k + 2) % 3] < 0;
    edge_flag[3 * t + k] = open;
    if (open) on_boundary[tri.v[k]] = on_boundary[tri.v[(k + 1) % 3]] = 1;
    used[tri.v[k]] = 1;
    atomicAdd(&valence[tri.v[k]], 1);
  }
}

// counts[1]: unused points; counts[2]: free interior nodes of valence three (trapped_nodes.h).
__global__ void count_nodes(DeviceSpan<const uint8_t> used, DeviceSpan<const uint8_t> on_boundary,
                            DeviceSpan<const int32_t> valence, int64_t nfix, int32_t* counts) {
  const int64_t i = thread_index();
  if (i >= used.size) return;
  if (!used[i]) atomicAdd(&counts[1], 1);
  if (i >= nfix && valence[i] == 3 && !on_boundary[i]) atomicAdd(&counts[2], 1);
}

__global__ void scatter_flagged(DeviceSpan<const uint8_t> flag, DeviceSpan<const int32_t> position,
                                DeviceSpan<int32_t> out) {
  const int64_t i = thread_index();
  if (i < flag.size && flag[i]) out[position[i]] = static_cast<int32_t>(i);
}

// The indices i with flag[i], increasing.
std::vector<int32_t> flagged_indices(DeviceSpan<const uint8_t> flag,
                                     DeviceBuffer<int32_t>& position, DeviceBuffer<int32_t>& ids,
                                     DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  position.resize(flag.size);
  exclusive_scan(flag.data, position.data(), flag.size, temp, stream);
  const int64_t total = scan_total(position.data(), flag.data, flag.size, stream);
  ids.resize(total);
  if (total > 0) {
    scatter_flagged<<<blocks_for(flag.size), kBlock, 0, stream>>>(flag, position.span(),
                                                                  ids.span());
    MESHD_CHECK_LAUNCH("scatter_flagged");
  }
  std::vector<int32_t> out(total);
  ids.download(out.data(), stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  return out;
}

struct QualityOp {
  __device__ QualitySums operator()(const QualitySums& a, const QualitySums& b) const {
    QualitySums r;
    r.sum = a.sum + b.sum;
    r.q_min = fmin(a.q_min, b.q_min);
    r.angle_min = fmin(a.angle_min, b.angle_min);
    for (int k = 0; k < kQualityBins; ++k) r.histogram[k] = a.histogram[k] + b.histogram[k];
    return r;
  }
};

__device__ QualitySums no_triangles() { return {0.0, INFINITY, 180.0, {}}; }

__global__ void __launch_bounds__(kBlock)
    sum_quality(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                DeviceSpan<QualitySums> partial) {
  using Reduce = cub::BlockReduce<QualitySums, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  QualitySums sums = no_triangles();
  const int64_t stride = static_cast<int64_t>(gridDim.x) * blockDim.x;
  for (int64_t t = thread_index(); t < tris.size; t += stride) {
    const Tri tri = tris[t];
    const Vec2 a = p[tri.v[0]], b = p[tri.v[1]], c = p[tri.v[2]];
    const double q = radius_ratio(a, b, c);
    sums.sum += q;
    sums.q_min = fmin(sums.q_min, q);
    sums.angle_min = fmin(sums.angle_min, min_angle_deg(a, b, c));
    const int bin = min(max(static_cast<int>(q * kQualityBins), 0), kQualityBins - 1);
    ++sums.histogram[bin];
  }
  const QualitySums total = Reduce(temp).Reduce(sums, QualityOp{});
  if (threadIdx.x == 0) partial[blockIdx.x] = total;
}

// One block sums the partials in a fixed order: the same bits every run. Its summands are too
// large for 1024 threads' registers; 256 read four partials each.
constexpr int kFinishBlock = kBlock;

__global__ void __launch_bounds__(kFinishBlock) total_quality(DeviceSpan<QualitySums> partial) {
  using Reduce = cub::BlockReduce<QualitySums, kFinishBlock>;
  __shared__ typename Reduce::TempStorage temp;
  QualitySums sums = no_triangles();
  for (int64_t i = threadIdx.x; i < partial.size; i += blockDim.x)
    sums = QualityOp{}(sums, partial[i]);
  const QualitySums total = Reduce(temp).Reduce(sums, QualityOp{});
  if (threadIdx.x == 0) partial[0] = total;
}

}  // namespace

MeshFacts find_mesh_facts(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                          DeviceSpan<const Tri> nbrs, double below_quality, int64_t nfix,
                          FinishScratch& s, DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  const int64_t m = tris.size;
  s.edge_flag.resize(3 * m);
  s.below_flag.resize(m);
  s.used.resize(p.size);
  s.on_boundary.resize(p.size);
  s.valence.resize(p.size);
  s.counts.resize(3);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.counts.data(), 0, 3 * sizeof(int32_t), stream));
  if (p.size > 0) {
    MESHD_CUDA_CHECK(cudaMemsetAsync(s.used.data(), 0, p.size, stream));
    MESHD_CUDA_CHECK(cudaMemsetAsync(s.on_boundary.data(), 0, p.size, stream));
    MESHD_CUDA_CHECK(cudaMemsetAsync(s.valence.data(), 0, p.size * sizeof(int32_t), stream));
  }
  if (m > 0) {
    flag_triangle_facts<<<blocks_for(m), kBlock, 0, stream>>>(
        p, tris, nbrs, below_quality, s.edge_flag.span(), s.below_flag.span(), s.used.span(),
        s.on_boundary.span(), s.valence.span(), s.counts.data());
    MESHD_CHECK_LAUNCH("flag_triangle_facts");
  }
  if (p.size > 0) {
    count_nodes<<<blocks_for(p.size), kBlock, 0, stream>>>(s.used.span(), s.on_boundary.span(),
                                                           s.valence.span(), nfix, s.counts.data());
    MESHD_CHECK_LAUNCH("count_nodes");
  }
  MeshFacts facts;
  facts.boundary = flagged_indices(s.edge_flag.span(), s.edge_position, s.ids, temp, stream);
  facts.below = flagged_indices(s.below_flag.span(), s.below_position, s.ids, temp, stream);
  int32_t counts[3];
  s.counts.download(counts, stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  facts.tidy = counts[0] == 0 && counts[1] == 0;
  facts.none_trapped = counts[2] == 0;
  return facts;
}

QualityStats measure_quality(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris, FinishScratch& s,
                             cudaStream_t stream) {
  QualityStats stats;
  if (tris.size == 0) return stats;
  const int64_t blocks = reduce_blocks_for(tris.size);
  s.partial.resize(blocks);
  sum_quality<<<blocks, kBlock, 0, stream>>>(p, tris, s.partial.span());
  MESHD_CHECK_LAUNCH("sum_quality");
  total_quality<<<1, kFinishBlock, 0, stream>>>(s.partial.span());
  MESHD_CHECK_LAUNCH("total_quality");
  QualitySums total;
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(&total, s.partial.data(), sizeof(total), cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  stats.q_min = total.q_min;
  stats.q_mean = total.sum / static_cast<double>(tris.size);
  stats.min_angle_deg = total.angle_min;
  for (int k = 0; k < kQualityBins; ++k) stats.histogram[k] = total.histogram[k];
  return stats;
}

}  // namespace meshd::gpu
