// The 3D DistMesh steps 4-8 on the device, the arithmetic of step3d.cpp: bar lengths and the
// volume-matching L0 scale (a deterministic two-stage reduction), forces gathered per node
// through the bar CSR in the CPU engine's order (no atomics), the Euler step with momentum, the
// projection of nodes that left the domain, and the termination measures.
#include <cub/block/block_reduce.cuh>

#include "core/geometry3d/gradient3.cuh"
#include "core/geometry3d/sdf3_eval.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"
#include "kernels/launch3d.h"

namespace meshd::gpu {
namespace {

struct SumBars3 {
  __device__ BarSums3 operator()(BarSums3 a, BarSums3 b) const {
    return {a.l3 + b.l3, a.h3 + b.h3};
  }
};

// max, max, sum, sum.
struct StepOp3 {
  __device__ StepSums3 operator()(StepSums3 a, StepSums3 b) const {
    return {fmax(a.max_move, b.max_move), fmax(a.max_drift, b.max_drift), a.sum_sq + b.sum_sq,
            a.interior + b.interior};
  }
};

constexpr int kFinishBlock = 1024;

__device__ int64_t first_item() {
  return blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
}
__device__ int64_t grid_stride() { return static_cast<int64_t>(gridDim.x) * blockDim.x; }

__global__ void measure_bars3(DeviceSpan<const Vec3> p, DeviceSpan<const Bar3> bars,
                              SizeField3View fh, bool graded, DeviceSpan<double> length,
                              DeviceSpan<double> size, DeviceSpan<BarSums3> partial) {
  using Reduce = cub::BlockReduce<BarSums3, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  BarSums3 sums{0.0, 0.0};
  for (int64_t b = first_item(); b < bars.size; b += grid_stride()) {
    const Vec3 a = p[bars[b].a], e = p[bars[b].b];
    const double len = norm(a - e);
    const double h = graded ? eval_size3(fh, 0.5 * (a + e)) : 1.0;
    length[b] = len;
    size[b] = h;
    sums = SumBars3{}(sums, {len * len * len, h * h * h});
  }
  const BarSums3 total = Reduce(temp).Reduce(sums, SumBars3{});
  if (threadIdx.x == 0) partial[blockIdx.x] = total;
}

__global__ void finish_scale3(DeviceSpan<const BarSums3> partial, double fscale, double* scale) {
  using Reduce = cub::BlockReduce<BarSums3, kFinishBlock>;
  __shared__ typename Reduce::TempStorage temp;
  BarSums3 sums{0.0, 0.0};
  for (int64_t i = threadIdx.x; i < partial.size; i += blockDim.x)
    sums = SumBars3{}(sums, partial[i]);
  const BarSums3 total = Reduce(temp).Reduce(sums, SumBars3{});
  if (threadIdx.x == 0) scale[0] = total.h3 > 0.0 ? fscale * cbrt(total.l3 / total.h3) : 0.0;
}

// The program's distance, capped as the host's Domain3 caps it.
struct CompiledDistance3 {
  Program3View fd;
  double band;
  __device__ double operator()(Vec3 p) const { return eval_sdf3(fd, p, nullptr, band); }
};

__device__ StepSums3 move_node3(const MoveArgs3& a, int64_t i) {
  const double scale = *a.scale;
  Vec3 force{0.0, 0.0, 0.0};
  double own = 0.0;
  const int64_t first = a.bar_offsets[i], last = a.bar_offsets[i + 1];
  for (int64_t k = first; k < last; ++k) {
    const int64_t e = a.bar_ends[k];
    const int64_t b = e >> 1;
    const double desired = a.size[b] * scale;
    const double length = a.length[b];
    const double f = fmax(desired - length, 0.0);
    const Vec3 bar = a.p[a.bars[b].a] - a.p[a.bars[b].b];
    const Vec3 push = length > 0.0 ? (f / length) * bar : Vec3{0.0, 0.0, 0.0};
    force = (e & 1) ? force - push : force + push;
    own += desired;
  }
  own = last > first ? own / static_cast<double>(last - first) : a.h0;
  const Vec3 here = a.p[i];
  if (i < a.fixed) {
    a.p_next[i] = here;
    return {0.0, 0.0, 0.0, 0.0};
  }
  const Vec3 move = a.deltat * force + a.momentum_factor * a.momentum[i];
  a.momentum[i] = move;
  Vec3 q = here + move;
  const CompiledDistance3 distance{a.fd, a.band};
  const double d = distance(q);
  if (d > 0.0) q = project_step3(distance, q, d, a.deps);
  a.p_next[i] = q;
  StepSums3 out{0.0, norm(q - a.at_triangulation[i]) / own, 0.0, 0.0};
  if (d < a.inside) {
    const double m = norm(move) / own;
    out.max_move = m;
    out.sum_sq = m * m;
    out.interior = 1.0;
  }
  return out;
}

__global__ void move_nodes3(MoveArgs3 a) {
  using Reduce = cub::BlockReduce<StepSums3, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  StepSums3 sums{0.0, 0.0, 0.0, 0.0};
  for (int64_t i = first_item(); i < a.p.size; i += grid_stride())
    sums = StepOp3{}(sums, move_node3(a, i));
  const StepSums3 total = Reduce(temp).Reduce(sums, StepOp3{});
  if (threadIdx.x == 0) a.partial[blockIdx.x] = total;
}

__global__ void finish_step3(DeviceSpan<const StepSums3> partial, StepResult* result) {
  using Reduce = cub::BlockReduce<StepSums3, kFinishBlock>;
  __shared__ typename Reduce::TempStorage temp;
  StepSums3 m{0.0, 0.0, 0.0, 0.0};
  for (int64_t i = threadIdx.x; i < partial.size; i += blockDim.x) m = StepOp3{}(m, partial[i]);
  const StepSums3 total = Reduce(temp).Reduce(m, StepOp3{});
  if (threadIdx.x != 0) return;
  StepResult r;
  r.max_move = total.max_move;
  r.max_drift = total.max_drift;
  r.rms_move = total.interior > 0.0 ? sqrt(total.sum_sq / total.interior) : 0.0;
  *result = r;
}

__global__ void mark_crowded3(DeviceSpan<const Bar3> bars, DeviceSpan<const double> length,
                              DeviceSpan<const double> size, const double* scale, int64_t fixed,
                              DeviceSpan<uint8_t> flags) {
  const int64_t b = first_item();
  if (b >= bars.size) return;
  if (!(size[b] * *scale > 2.0 * length[b])) return;
  // Several bars may flag one node: every writer writes the same 1.
  if (bars[b].a >= fixed) flags[bars[b].a] = 1;
  if (bars[b].b >= fixed) flags[bars[b].b] = 1;
}

}  // namespace

void launch_measure_bars3(DeviceSpan<const Vec3> p, DeviceSpan<const Bar3> bars, SizeField3View fh,
                          bool graded, DeviceSpan<double> length, DeviceSpan<double> size,
                          DeviceSpan<BarSums3> partial, cudaStream_t stream) {
  // Launched even without bars, so that the partial reads as zero sums.
  measure_bars3<<<partial.size, kBlock, 0, stream>>>(p, bars, fh, graded, length, size, partial);
  MESHD_CHECK_LAUNCH("measure_bars3");
}

void launch_finish_scale3(DeviceSpan<const BarSums3> partial, double fscale, double* scale,
                          cudaStream_t stream) {
  finish_scale3<<<1, kFinishBlock, 0, stream>>>(partial, fscale, scale);
  MESHD_CHECK_LAUNCH("finish_scale3");
}

void launch_move_nodes3(const MoveArgs3& args, cudaStream_t stream) {
  if (args.p.size == 0) return;
  move_nodes3<<<args.partial.size, kBlock, 0, stream>>>(args);
  MESHD_CHECK_LAUNCH("move_nodes3");
}

void launch_finish_step3(DeviceSpan<const StepSums3> partial, StepResult* result,
                         cudaStream_t stream) {
  finish_step3<<<1, kFinishBlock, 0, stream>>>(partial, result);
  MESHD_CHECK_LAUNCH("finish_step3");
}

void launch_mark_crowded3(DeviceSpan<const Bar3> bars, DeviceSpan<const double> length,
                          DeviceSpan<const double> size, const double* scale, int64_t fixed,
                          DeviceSpan<uint8_t> flags, cudaStream_t stream) {
  if (bars.size == 0) return;
  mark_crowded3<<<blocks_for(bars.size), kBlock, 0, stream>>>(bars, length, size, scale, fixed,
                                                              flags);
  MESHD_CHECK_LAUNCH("mark_crowded3");
}

}  // namespace meshd::gpu
