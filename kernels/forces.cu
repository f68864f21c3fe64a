// DistMesh steps 4-8 on the device: bar lengths and the L0 scale (a deterministic reduction),
// forces gathered per node through the bar CSR (no atomics: reproducible bits), the Euler step
// with momentum, the projection onto the boundary, and the termination measures.
#include <cooperative_groups.h>

#include <cub/block/block_reduce.cuh>

#include "core/geometry/projection.cuh"
#include "core/geometry/size_eval.cuh"
#include "kernels/cooperative_launch.h"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"

namespace meshd::gpu {
namespace {

namespace cg = cooperative_groups;

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

using BarReduce = cub::BlockReduce<BarSums, kBlock>;

// Block `block` of `blocks` of the bars' measure (step 4): its bars' lengths and sizes, stored
// where given (size > 0: the step needs the sizes of a graded field, density control needs both),
// and their sums, whole on thread 0. measure_bars runs one such block a block; the cooperative
// steps run every block's in turn, so that both give the partials the same bits.
template <bool kUniform>
__device__ BarSums measure_block(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars,
                                 const SizeView& fh, DeviceSpan<double> length,
                                 DeviceSpan<double> size, int64_t block, int64_t blocks,
                                 BarReduce::TempStorage& temp) {
  BarSums sums{0.0, 0.0};
  const int64_t stride = blocks * kBlock;
  for (int64_t b = block * kBlock + threadIdx.x; b < bars.size; b += stride) {
    const Vec2 a = p[bars[b].a], e = p[bars[b].b];
    const double len = norm(a - e);
    double h = 1.0;
    if constexpr (!kUniform) h = eval_size(fh, 0.5 * (a + e));
    if (length.size > 0) length[b] = len;
    if (size.size > 0) size[b] = h;
    sums = SumPair{}(sums, {len * len, h * h});
  }
  return BarReduce(temp).Reduce(sums, SumPair{});
}
// The blocks' partials summed in the order of their indices, whichever block sums them; the
// total on thread 0.
__device__ BarSums sum_bar_partials(const BarSums* partial, int64_t blocks,
                                    BarReduce::TempStorage& temp) {
  BarSums sums{0.0, 0.0};
  for (int64_t i = threadIdx.x; i < blocks; i += kBlock)
    sums = SumPair{}(sums, {__ldcg(&partial[i].l2), __ldcg(&partial[i].h2)});
  return BarReduce(temp).Reduce(sums, SumPair{});
}
__device__ double bars_scale(const BarSums& total, double fscale) {
  return total.h2 > 0.0 ? fscale * sqrt(total.l2 / total.h2) : 0.0;
}

// Uniform is a template parameter: without the size evaluator the kernel fits 32 registers and
// eight blocks per SM, so that its kMaxReduceBlocks blocks run as one wave.
// The last block to finish sums the blocks' partials and writes the scale: one launch where a
// second, one block's, cost a small job one more of the calls that bound many small jobs at once
// (bench/RESULTS.md).
template <bool kUniform>
__global__ void __launch_bounds__(kBlock, kUniform ? 8 : 2)
    measure_bars(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars, SizeView fh,
                 DeviceSpan<double> length, DeviceSpan<double> size, BarsMeasure m) {
  __shared__ BarReduce::TempStorage temp;
  __shared__ bool last;
  const BarSums block_total =
      measure_block<kUniform>(p, bars, fh, length, size, blockIdx.x, gridDim.x, temp);
  if (threadIdx.x == 0) {
    m.partial[blockIdx.x] = block_total;
    __threadfence();  // the partial is visible before the ticket says so
    last = atomicAdd(m.ticket, 1u) == gridDim.x - 1;
  }
  __syncthreads();
  if (!last) return;
  const BarSums total = sum_bar_partials(m.partial, gridDim.x, temp);
  if (threadIdx.x != 0) return;
  m.scale[0] = bars_scale(total, m.fscale);
  m.scale[1] = total.h2;  // for the lagged scale of the steps until the next triangulation
  *m.ticket = 0;          // for the next launch on this stream
}

// The one-block kernels that sum the partials run 1024 threads: each reads a few partials, where
// 256 threads each read a dozen one after the other.
constexpr int kFinishBlock = 1024;

// Gathers the far ends of CSR entries [k, end) a few at a time: their loads are independent, and
// issuing them together hides the latency that one load after the other would expose (3% of a
// step at a million nodes on an H200, against one at a time).
constexpr int kGatherBatch = 4;

// The measures of node i's step (StepOp's identity for a fixed node but its bars' L^2), under the
// L0 scale `scale`.
__device__ StepSums move_node(const MoveArgs& a, int64_t i, double scale) {
  const Vec2 here = a.p[i];
  const bool gather = a.scattered.size == 0;
  Vec2 total{0.0, 0.0};
  double l2 = 0.0, size_sum = 0.0;
  if (!gather) total = {a.scattered[2 * i], a.scattered[2 * i + 1]};
  const int32_t first = a.csr_offset[i], last = a.csr_offset[i + 1];
  const int32_t begin = gather ? first : 0, end = gather ? last : 0;
  for (int32_t k = begin; k < end; k += kGatherBatch) {
    Vec2 other[kGatherBatch];
#pragma unroll
    for (int j = 0; j < kGatherBatch; ++j) other[j] = k + j < end ? a.p[a.csr_other[k + j]] : here;
#pragma unroll
    for (int j = 0; j < kGatherBatch; ++j) {
      if (k + j >= end) break;
      // The vector from the other end: at the bar's second end it is the bar vector
      // p[a] - p[b] negated, which is exact, so the length and the force come out bitwise as
      // measure_bars and the CPU engine compute them, with the sign.
      const Vec2 v = here - other[j];
      const double len = norm(v);
      l2 += len * len;
      if (i < a.nfix) continue;  // fixed nodes: their bars count towards the lagged scale only
      const double h = a.uniform ? 1.0 : a.size[a.csr_entry[k + j] >> 1];
      size_sum += h;
      const double f = fmax(h * scale - len, 0.0);
      total = total + (len > 0.0 ? (f / len) * v : Vec2{0.0, 0.0});
    }
  }
  StepSums measures{0.0, 0.0, 0.0, 0.0, l2};
  if (i < a.nfix) {
    a.p_next[i] = here;  // fixed nodes stay exactly where they are
    return measures;
  }
  const Vec2 step = a.deltat * total + a.momentum * a.velocity[i];
  a.velocity[i] = step;
  Vec2 q = here + step;
  // Far enough inside, d's value decides nothing (clearance.cuh): its bound stands in.
  const double inside = a.clear.carried(a.clearance[i], norm(step));
  const double d = a.clear.decides(inside) ? -inside : eval_sdf(a.fd, q, a.nested_index);
  a.clearance[i] = round_down_to_float(-d);
  if (d > 0.0) q = project_step(a.fd, q, d, a.deps, a.nested_index);
  a.on_boundary[i] = d >= -a.near_boundary;
  a.p_next[i] = q;
  // Moves are measured in the node's own size (step_rule.cuh): h0 * the mean h of its bars. The
  // atomic sums skipped the loop above, so there the sizes are read here.
  if (!gather && !a.uniform)
    for (int32_t k = first; k < last; ++k) size_sum += a.size[a.csr_entry[k] >> 1];
  const double unit = a.uniform || last == first ? a.h0 : a.h0 * (size_sum / (last - first));
  const double move = norm(step) / unit;
  if (d < -a.geps) measures = {move, 0.0, move * move, 1.0, l2};
  measures.max_drift = norm(q - a.p_old[i]) / unit;
  return measures;
}

// The block's threads copy `bytes` of device memory to `to`, word by word, then meet. The loads
// bypass L1 (__ldcg): another block or kernel wrote the words.
__device__ void copy_words(void* to, const void* from, size_t bytes) {
  for (size_t w = threadIdx.x; w < bytes / sizeof(uint64_t); w += blockDim.x)
    reinterpret_cast<uint64_t*>(to)[w] =
        __ldcg(reinterpret_cast<const unsigned long long*>(from) + w);
  __syncthreads();
}
// Each block copies the step's arguments to shared memory once: they live in device memory,
// where the step before swapped p and p_next.
__device__ void load_move_args(MoveArgs& a, const StepBatch* batch) {
  static_assert(sizeof(MoveArgs) % sizeof(uint64_t) == 0);
  copy_words(&a, &batch->args, sizeof(MoveArgs));
}

using StepReduce = cub::BlockReduce<StepSums, kBlock>;

// Moves this block's nodes (block b of a.partial.size takes every that many blocks' worth) under
// the L0 scale `scale` and writes their measures to partial[b].
__device__ void move_block_nodes(const MoveArgs& a, double scale, StepSums* partial,
                                 StepReduce::TempStorage& temp) {
  StepSums measures{0.0, 0.0, 0.0, 0.0, 0.0};
  const int64_t stride = a.partial.size * blockDim.x;
  for (int64_t i = blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x; i < a.p.size;
       i += stride)
    measures = StepOp{}(measures, move_node(a, i, scale));
  const StepSums total = StepReduce(temp).Reduce(measures, StepOp{});
  if (threadIdx.x == 0) partial[blockIdx.x] = total;
}

// Three blocks per SM: the bound keeps the kernel at 80 registers (without it, 92 and two blocks,
// which made the step 10% slower at a million nodes; the gathers are latency-bound).
__global__ void __launch_bounds__(kBlock, 3) move_nodes(const StepBatch* batch) {
  __shared__ MoveArgs a;
  __shared__ StepReduce::TempStorage temp;
  load_move_args(a, batch);
  if (blockIdx.x >= a.partial.size) return;
  move_block_nodes(a, *a.scale, a.partial.data, temp);
}

// The step's partials summed in an order that does not depend on the summing block's size, so
// that finish_step and the cooperative steps give the same bits: runs of 32 partials each summed
// by one warp's shuffle tree, then the runs' sums one after the other. Every thread of the block
// calls it; thread 0's value is the total.
constexpr int kMaxStepPartials = 2048;
constexpr int kWarp = 32;
struct PartialRuns {
  StepSums run[kMaxStepPartials / kWarp];
};
__device__ StepSums sum_step_partials(DeviceSpan<const StepSums> partial, PartialRuns& runs) {
  const int lane = threadIdx.x % kWarp, warp = threadIdx.x / kWarp, warps = blockDim.x / kWarp;
  const int count = static_cast<int>((partial.size + kWarp - 1) / kWarp);
  for (int r = warp; r < count; r += warps) {
    const int64_t i = static_cast<int64_t>(r) * kWarp + lane;
    StepSums v = i < partial.size ? partial[i] : StepSums{0.0, 0.0, 0.0, 0.0, 0.0};
    for (int offset = kWarp / 2; offset > 0; offset /= 2) {
      const StepSums o{__shfl_down_sync(0xffffffffu, v.max_move, offset),
                       __shfl_down_sync(0xffffffffu, v.max_drift, offset),
                       __shfl_down_sync(0xffffffffu, v.sum_sq, offset),
                       __shfl_down_sync(0xffffffffu, v.interior, offset),
                       __shfl_down_sync(0xffffffffu, v.bar_l2, offset)};
      v = StepOp{}(v, o);
    }
    if (lane == 0) runs.run[r] = v;
  }
  __syncthreads();
  StepSums total{0.0, 0.0, 0.0, 0.0, 0.0};
  if (threadIdx.x == 0)
    for (int r = 0; r < count; ++r) total = StepOp{}(total, runs.run[r]);
  return total;
}

// The end of a step, on one thread: its result, the lagged L0 scale for the next step (into
// *scale) from h2, the bars' sum of h^2 as measured at the triangulation (next_scale[1]; 0 where
// there is no lagged scale), the positions swapped, the settling record carried on. Returns
// whether another step follows: fewer than `limit` ran and the rule does not stop here.
__device__ bool end_step(StepBatch& b, const StepSums& total, double h2, double* scale) {
  // Each bar was measured from both ends.
  if (h2 > 0.0) *scale = b.fscale * sqrt(0.5 * total.bar_l2 / h2);
  StepResult r;
  r.max_move = total.max_move;
  r.max_drift = total.max_drift;
  r.rms_move = total.interior > 0.0 ? sqrt(total.sum_sq / total.interior) : 0.0;
  const int32_t k = b.count++;
  b.results[k] = r;
  Vec2* const moved = b.args.p_next.data;
  b.args.p_next.data = const_cast<Vec2*>(b.args.p.data);
  b.args.p.data = moved;
  // The batch's copy of the rule carries the settling record on from step to step.
  b.rule.settling = b.rule.settle(b.rule.settling, r);
  return k + 1 < b.limit && !b.rule.stops(r, b.first_iteration + k, b.rule.settling);
}

// The cooperative steps' argument: the batch comes with the launch.
struct StepsTogether {
  StepBatch head;                  // the batch as the host set it up
  StepBatch* batch;                // where it ends
  StepsMeasure measure;            // the bars' measure first, where on
  const TopologyCounters* repair;  // where given, the repair the steps ride behind
};
static_assert(sizeof(StepsTogether) <= 4096, "a kernel's parameters: at most 4 KiB");

// A batch's steps in one cooperative launch, one block per partial, with one grid barrier a step:
// each block keeps its own copy of the batch, moves its nodes, and after the barrier sums every
// block's partial and ends the step on its copy (the same bits in every block, so each knows the
// next step's scale and whether it comes without a second barrier); block 0 writes its copy
// back when the batch ends. The steps alternate between the two halves of the partials, so that
// a block writing the next step's partial cannot overwrite one that a slower block still reads.
// In place of the graph loop's two launches a step: at 20k nodes on an H200, 18 us a step
// against 23 (with two barriers a step).
// Where the batch starts after a triangulation, the bars' measure comes first, every measure
// block's in turn and one grid barrier; every block then sums the partials itself, in
// measure_bars' order, so that the scale has its bits without a second barrier.
// Behind a repair whose outcome the host has not read yet, the steps run where it settled on the
// device: one wait for both where the host would wait for each (a small job's retriangulations).
__global__ void __launch_bounds__(kBlock, 3)
    steps_together(const __grid_constant__ StepsTogether t) {
  // Every block reads the same counters, so all return or none, before any grid barrier. Without
  // bars the host takes lone steps of the exact scale instead.
  if (t.repair != nullptr && (!settled_on_device(*t.repair) || *t.measure.bar_count == 0)) return;
  const cg::grid_group grid = cg::this_grid();
  __shared__ StepBatch b;
  __shared__ union {
    StepReduce::TempStorage step;
    BarReduce::TempStorage bars;
  } temp;
  __shared__ PartialRuns runs;
  __shared__ double scale, h2;
  __shared__ bool more;
  static_assert(sizeof(StepBatch) % sizeof(uint64_t) == 0);
  for (size_t w = threadIdx.x; w < sizeof(StepBatch) / sizeof(uint64_t); w += blockDim.x)
    reinterpret_cast<uint64_t*>(&b)[w] = reinterpret_cast<const uint64_t*>(&t.head)[w];
  __syncthreads();
  const StepsMeasure& m = t.measure;
  if (m.on) {
    // The count on the device where the host has not read it: measure_bars' blocks for it.
    const DeviceSpan<const Bar> bars{m.bars.data, m.bar_count ? *m.bar_count : m.bars.size};
    const int64_t blocks = m.bar_count ? nonempty_reduce_blocks_for(bars.size) : m.blocks;
    for (int64_t block = blockIdx.x; block < blocks; block += gridDim.x) {
      const BarSums sums =
          m.uniform
              ? measure_block<true>(b.args.p, bars, m.fh, {}, m.size, block, blocks, temp.bars)
              : measure_block<false>(b.args.p, bars, m.fh, {}, m.size, block, blocks, temp.bars);
      if (threadIdx.x == 0) m.partial[block] = sums;
      __syncthreads();  // temp is reused
    }
    grid.sync();
    const BarSums total = sum_bar_partials(m.partial, blocks, temp.bars);
    if (threadIdx.x == 0) {
      scale = bars_scale(total, b.fscale);
      h2 = total.h2;
      // For the batches until the next triangulation, as measure_bars leaves it; block 0 writes
      // next_scale[0] when the batch ends.
      if (blockIdx.x == 0 && b.next_scale != nullptr) b.next_scale[1] = h2;
    }
  } else if (threadIdx.x == 0) {
    scale = __ldcg(b.args.scale);
    h2 = b.next_scale != nullptr ? __ldcg(&b.next_scale[1]) : 0.0;
  }
  __syncthreads();
  for (int step = 0;; ++step) {
    const DeviceSpan<StepSums> partial{b.args.partial.data + (step % 2) * b.args.partial.size,
                                       b.args.partial.size};
    move_block_nodes(b.args, scale, partial.data, temp.step);
    grid.sync();
    const StepSums total = sum_step_partials(partial, runs);
    if (threadIdx.x == 0) b.more = more = end_step(b, total, h2, &scale);
    __syncthreads();
    if (!more) break;
  }
  if (blockIdx.x != 0) return;
  for (size_t w = threadIdx.x; w < sizeof(StepBatch) / sizeof(uint64_t); w += blockDim.x)
    reinterpret_cast<uint64_t*>(t.batch)[w] = reinterpret_cast<const uint64_t*>(&b)[w];
  if (threadIdx.x == 0 && b.next_scale != nullptr) b.next_scale[0] = scale;
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

// in_graph: launched by the step graph, whose loop condition `more` it sets.
__global__ void finish_step(StepBatch* batch, bool in_graph, cudaGraphConditionalHandle more) {
  __shared__ PartialRuns runs;
  const StepSums total = sum_step_partials(batch->args.partial, runs);
  if (threadIdx.x != 0) return;
  const double h2 = batch->next_scale != nullptr ? batch->next_scale[1] : 0.0;
  const bool again = end_step(*batch, total, h2, batch->next_scale);
  if (in_graph) cudaGraphSetConditional(more, again);
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
                         const BarsMeasure& m, cudaStream_t stream) {
  const int64_t blocks = nonempty_reduce_blocks_for(bars.size);
  if (uniform)
    measure_bars<true><<<blocks, kBlock, 0, stream>>>(p, bars, fh, length, size, m);
  else
    measure_bars<false><<<blocks, kBlock, 0, stream>>>(p, bars, fh, length, size, m);
  MESHD_CHECK_LAUNCH("measure_bars");
}

int64_t move_nodes_wave(int device) {
  return std::min<int64_t>(resident_blocks(move_nodes, kBlock, device), kMaxStepPartials);
}

bool steps_together_fit(int device, int64_t blocks) {
  return blocks <= cooperative_blocks(steps_together, kBlock, device);
}

void launch_steps_together(const StepBatch& head, StepBatch* batch, const StepsMeasure& measure,
                           int64_t blocks, cudaStream_t stream, const TopologyCounters* repair) {
  launch_cooperative(steps_together, blocks, kBlock, StepsTogether{head, batch, measure, repair},
                     stream, "steps_together");
}

void launch_move_nodes(const StepBatch* batch, int64_t blocks, cudaStream_t stream) {
  move_nodes<<<blocks, kBlock, 0, stream>>>(batch);
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

void launch_finish_step(StepBatch* batch, const cudaGraphConditionalHandle* more,
                        cudaStream_t stream) {
  finish_step<<<1, kFinishBlock, 0, stream>>>(batch, more != nullptr, more != nullptr ? *more : 0);
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
