// DistMesh steps 4-8 on the device: bar lengths and the L0 scale (a deterministic reduction),
// forces gathered per node through the bar CSR (no atomics: reproducible bits), the Euler step
// with momentum, the projection onto the boundary, and the termination measures.
#include <cub/block/block_reduce.cuh>

#include "core/geometry/projection.cuh"
#include "core/geometry/size_eval.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"

namespace meshd::gpu {
namespace {

struct SumPair {
  __device__ BarSums operator()(BarSums a, BarSums b) const { return {a.l2 + b.l2, a.h2 + b.h2}; }
};

// max, max, sum, sum: the four step measures.
struct StepOp {
  __device__ StepSums operator()(StepSums a, StepSums b) const {
    return {fmax(a.max_move, b.max_move), fmax(a.max_drift, b.max_drift), a.sum_sq + b.sum_sq,
            a.interior + b.interior, a.bar_l2 + b.bar_l2};
  }
};

__global__ void measure_bars(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars, SizeView fh,
                             bool uniform, DeviceSpan<double> length, DeviceSpan<double> size,
                             DeviceSpan<BarSums> partial) {
  // length and size are written only where given (size > 0): the step needs the sizes of a
  // graded field, density control needs both.
  using Reduce = cub::BlockReduce<BarSums, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  const int64_t b = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  BarSums sums{0.0, 0.0};
  if (b < bars.size) {
    const Vec2 a = p[bars[b].a], e = p[bars[b].b];
    const double len = norm(a - e);
    const double h = uniform ? 1.0 : eval_size(fh, 0.5 * (a + e));
    if (length.size > 0) length[b] = len;
    if (size.size > 0) size[b] = h;
    sums = {len * len, h * h};
  }
  const BarSums total = Reduce(temp).Reduce(sums, SumPair{});
  if (threadIdx.x == 0) partial[blockIdx.x] = total;
}

__global__ void finish_scale(DeviceSpan<const BarSums> partial, double fscale, double* scale) {
  using Reduce = cub::BlockReduce<BarSums, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  BarSums sums{0.0, 0.0};
  for (int64_t i = threadIdx.x; i < partial.size; i += blockDim.x)
    sums = SumPair{}(sums, partial[i]);
  const BarSums total = Reduce(temp).Reduce(sums, SumPair{});
  if (threadIdx.x == 0) *scale = total.h2 > 0.0 ? fscale * sqrt(total.l2 / total.h2) : 0.0;
}

__global__ void move_nodes(MoveArgs a) {
  using Reduce = cub::BlockReduce<StepSums, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  const int64_t i = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  StepSums measures{0.0, 0.0, 0.0, 0.0, 0.0};
  if (i < a.p.size) {
    const Vec2 here = a.p[i];
    if (i < a.nfix) {
      a.p_next[i] = here;  // fixed nodes stay exactly where they are
      // Their bars count towards the lagged scale's sum all the same.
      double l2 = 0.0;
      for (int32_t k = a.csr_offset[i]; k < a.csr_offset[i + 1] && a.scattered.size == 0; ++k) {
        const Vec2 other = a.p[a.csr_other[k]];
        l2 += dot(here - other, here - other);
      }
      measures.bar_l2 = l2;
    } else {
      Vec2 total{0.0, 0.0};
      double l2 = 0.0;
      if (a.scattered.size > 0) {
        total = {a.scattered[2 * i], a.scattered[2 * i + 1]};
      } else {
        const double scale = *a.scale;
        for (int32_t k = a.csr_offset[i]; k < a.csr_offset[i + 1]; ++k) {
          // The vector from the other end: at the bar's second end it is the bar vector
          // p[a] - p[b] negated, which is exact, so the length and the force come out bitwise
          // as measure_bars and the CPU engine compute them, with the sign.
          const Vec2 v = here - a.p[a.csr_other[k]];
          const double len = norm(v);
          l2 += len * len;
          const double h = a.uniform ? 1.0 : a.size[a.csr_entry[k] >> 1];
          const double f = fmax(h * scale - len, 0.0);
          total = total + (len > 0.0 ? (f / len) * v : Vec2{0.0, 0.0});
        }
      }
      const Vec2 step = a.deltat * total + a.momentum * a.velocity[i];
      a.velocity[i] = step;
      Vec2 q = here + step;
      const double d = eval_sdf(a.fd, q);
      if (d > 0.0) q = project_step(a.fd, q, d, a.deps);
      a.on_boundary[i] = d >= -a.near_boundary;
      a.p_next[i] = q;
      const double move2 = dot(step, step);
      if (d < -a.geps) measures = {sqrt(move2), 0.0, move2, 1.0, 0.0};
      measures.max_drift = norm(q - a.p_old[i]);
      measures.bar_l2 = l2;
    }
  }
  const StepSums total = Reduce(temp).Reduce(measures, StepOp{});
  if (threadIdx.x == 0) a.partial[blockIdx.x] = total;
}

__global__ void scatter_bar_forces(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars,
                                   DeviceSpan<const double> size, bool uniform, const double* scale,
                                   DeviceSpan<double> force) {
  const int64_t b = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (b >= bars.size) return;
  const Bar bar = bars[b];
  const Vec2 v = p[bar.a] - p[bar.b];
  const double len = norm(v);
  const double h = uniform ? 1.0 : size[b];
  const double f = fmax(h * *scale - len, 0.0);
  if (len <= 0.0 || f <= 0.0) return;
  const Vec2 fv = (f / len) * v;
  atomicAdd(&force[2 * bar.a], fv.x);
  atomicAdd(&force[2 * bar.a + 1], fv.y);
  atomicAdd(&force[2 * bar.b], -fv.x);
  atomicAdd(&force[2 * bar.b + 1], -fv.y);
}

__global__ void finish_step(DeviceSpan<const StepSums> partial, StepSums* out, double* next_scale,
                            double fscale, int64_t bars) {
  using Reduce = cub::BlockReduce<StepSums, kBlock>;
  __shared__ typename Reduce::TempStorage temp;
  StepSums m{0.0, 0.0, 0.0, 0.0, 0.0};
  for (int64_t i = threadIdx.x; i < partial.size; i += blockDim.x) m = StepOp{}(m, partial[i]);
  const StepSums total = Reduce(temp).Reduce(m, StepOp{});
  if (threadIdx.x != 0) return;
  *out = total;
  // Each bar was measured from both ends.
  if (next_scale != nullptr && bars > 0)
    *next_scale = fscale * sqrt(0.5 * total.bar_l2 / static_cast<double>(bars));
}

__global__ void mark_crowded(DeviceSpan<const Bar> bars, DeviceSpan<const double> length,
                             DeviceSpan<const double> size, const double* scale, int64_t nfix,
                             DeviceSpan<uint8_t> keep) {
  const int64_t b = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
  if (b >= bars.size || size[b] * *scale <= 2.0 * length[b]) return;
  if (bars[b].a >= nfix) keep[bars[b].a] = 0;
  if (bars[b].b >= nfix) keep[bars[b].b] = 0;
}

}  // namespace

void launch_measure_bars(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars, SizeView fh,
                         bool uniform, DeviceSpan<double> length, DeviceSpan<double> size,
                         DeviceSpan<BarSums> partial, cudaStream_t stream) {
  if (bars.size == 0) return;
  measure_bars<<<blocks_for(bars.size), kBlock, 0, stream>>>(p, bars, fh, uniform, length, size,
                                                             partial);
  MESHD_CHECK_LAUNCH("measure_bars");
}

void launch_finish_scale(DeviceSpan<const BarSums> partial, double fscale, double* scale,
                         cudaStream_t stream) {
  finish_scale<<<1, kBlock, 0, stream>>>(partial, fscale, scale);
  MESHD_CHECK_LAUNCH("finish_scale");
}

void launch_move_nodes(const MoveArgs& args, cudaStream_t stream) {
  if (args.p.size == 0) return;
  move_nodes<<<blocks_for(args.p.size), kBlock, 0, stream>>>(args);
  MESHD_CHECK_LAUNCH("move_nodes");
}

void launch_scatter_bar_forces(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars,
                               DeviceSpan<const double> size, bool uniform, const double* scale,
                               DeviceSpan<double> force, cudaStream_t stream) {
  if (bars.size == 0) return;
  scatter_bar_forces<<<blocks_for(bars.size), kBlock, 0, stream>>>(p, bars, size, uniform, scale,
                                                                   force);
  MESHD_CHECK_LAUNCH("scatter_bar_forces");
}

void launch_finish_step(DeviceSpan<const StepSums> partial, StepSums* out, double* next_scale,
                        double fscale, int64_t bars, cudaStream_t stream) {
  finish_step<<<1, kBlock, 0, stream>>>(partial, out, next_scale, fscale, bars);
  MESHD_CHECK_LAUNCH("finish_step");
}

void launch_mark_crowded(DeviceSpan<const Bar> bars, DeviceSpan<const double> length,
                         DeviceSpan<const double> size, const double* scale, int64_t nfix,
                         DeviceSpan<uint8_t> keep, cudaStream_t stream) {
  if (bars.size == 0) return;
  mark_crowded<<<blocks_for(bars.size), kBlock, 0, stream>>>(bars, length, size, scale, nfix, keep);
  MESHD_CHECK_LAUNCH("mark_crowded");
}

}  // namespace meshd::gpu
