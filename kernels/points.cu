// Initial points (DistMesh steps 1-2) and point compaction.
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"

namespace meshd::gpu {
namespace {

__global__ void classify_grid(InitialGrid grid, ProgramView fd, SizeView fh, double geps,
                              DeviceSpan<double> size, unsigned long long* h_min_bits) {
  const int64_t k = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (k >= size.size) return;
  const Vec2 q = initial_grid_point(grid, k);
  double h = 0.0;
  if (eval_sdf(fd, q) < geps) {
    h = eval_size(fh, q);
    // Positive doubles order like their bit patterns, so an integer atomicMin finds the min.
    atomicMin(h_min_bits, static_cast<unsigned long long>(__double_as_longlong(h)));
  }
  size[k] = h;
}

__global__ void flag_grid(InitialGrid grid, DeviceSpan<const double> size,
                          const unsigned long long* h_min_bits, uint64_t seed,
                          DeviceSpan<const Vec2> fixed, DeviceSpan<uint8_t> flag) {
  const int64_t k = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (k >= flag.size) return;
  const double h = size[k];
  const double h_min = __longlong_as_double(static_cast<long long>(*h_min_bits));
  bool keep = h > 0.0 && keep_by_size(seed, grid, k, h, h_min);
  if (keep) {
    const Vec2 q = initial_grid_point(grid, k);
    for (int64_t f = 0; f < fixed.size && keep; ++f) keep = norm(q - fixed[f]) >= 0.5 * grid.h0 * h;
  }
  flag[k] = keep;
}

__global__ void scatter_grid(InitialGrid grid, DeviceSpan<const uint8_t> flag,
                             DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out,
                             int64_t offset) {
  const int64_t k = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (k >= flag.size || !flag[k]) return;
  out[offset + position[k]] = initial_grid_point(grid, k);
}

__global__ void compact_points(DeviceSpan<const Vec2> in, DeviceSpan<const uint8_t> keep,
                               DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out) {
  const int64_t i = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (i >= in.size || !keep[i]) return;
  out[position[i]] = in[i];
}

}  // namespace

void launch_classify_grid(const InitialGrid& grid, ProgramView fd, SizeView fh, double geps,
                          DeviceSpan<double> size, unsigned long long* h_min_bits,
                          cudaStream_t stream) {
  if (size.size == 0) return;
  classify_grid<<<blocks_for(size.size), kBlock, 0, stream>>>(grid, fd, fh, geps, size, h_min_bits);
  MESHD_CHECK_LAUNCH("classify_grid");
}

void launch_flag_grid(const InitialGrid& grid, DeviceSpan<const double> size,
                      const unsigned long long* h_min_bits, uint64_t seed,
                      DeviceSpan<const Vec2> fixed, DeviceSpan<uint8_t> flag, cudaStream_t stream) {
  if (flag.size == 0) return;
  flag_grid<<<blocks_for(flag.size), kBlock, 0, stream>>>(grid, size, h_min_bits, seed, fixed,
                                                          flag);
  MESHD_CHECK_LAUNCH("flag_grid");
}

void launch_scatter_grid(const InitialGrid& grid, DeviceSpan<const uint8_t> flag,
                         DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out, int64_t offset,
                         cudaStream_t stream) {
  if (flag.size == 0) return;
  scatter_grid<<<blocks_for(flag.size), kBlock, 0, stream>>>(grid, flag, position, out, offset);
  MESHD_CHECK_LAUNCH("scatter_grid");
}

void launch_compact_points(DeviceSpan<const Vec2> in, DeviceSpan<const uint8_t> keep,
                           DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out,
                           cudaStream_t stream) {
  if (in.size == 0) return;
  compact_points<<<blocks_for(in.size), kBlock, 0, stream>>>(in, keep, position, out);
  MESHD_CHECK_LAUNCH("compact_points");
}

}  // namespace meshd::gpu
