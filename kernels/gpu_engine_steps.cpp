// GpuEngine::Impl's steps (4, 5, 7, 8): the bars' measure and batches of steps, through the step
// graph, one cooperative launch, or one launch a step (gpu_engine_impl.h).
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "kernels/gpu_engine_impl.h"

namespace meshd {

void GpuEngine::Impl::measure_bars(bool for_density_control) {
  size_measure(for_density_control);
  gpu::launch_measure_bars(
      p.span(), bars.span(), fh, uniform, length.span(), size.span(),
      {bar_partial.data(), last_block_ticket.data(), problem->params.fscale, scale.data()}, stream);
}

gpu::StepsMeasure GpuEngine::Impl::measure_in_steps() {
  return {.on = true,
          .uniform = uniform,
          .blocks = size_measure(false),
          .bars = bars.span(),
          .fh = fh,
          .size = size.span(),
          .partial = bar_partial.data()};
}

int64_t GpuEngine::Impl::size_measure(bool for_density_control) {
  const int64_t nb = static_cast<int64_t>(bars.size());
  const bool store_size = for_density_control || !uniform;
  length.resize(for_density_control ? nb : 0);
  size.resize(store_size ? nb : 0);
  const int64_t blocks = gpu::nonempty_reduce_blocks_for(nb);
  bar_partial.resize(blocks);
  scale.resize(2);
  return blocks;
}

int GpuEngine::Impl::run_steps(const StepRule& rule, int first_iteration, int limit) {
  const bool lagged = launch_steps(rule, first_iteration, limit);
  sync();
  return end_steps(lagged);
}

bool GpuEngine::Impl::lagged_steps() const {
  return lagged_scale && force_sum == ForceSum::kGather && bars.size() > 0;
}

bool GpuEngine::Impl::steps_go_together(int limit) const {
  return lagged_steps() && step_graph && std::min(limit, gpu::kMaxBatchSteps) > 1 &&
         steps_together && std::min(gpu::blocks_for(n), step_wave) < step_wave;
}

bool GpuEngine::Impl::launch_steps(const StepRule& rule, int first_iteration, int limit,
                                   const gpu::TopologyCounters* behind_repair) {
  const Params& prm = problem->params;
  const bool lagged = lagged_steps();
  if (!lagged || !step_graph) limit = 1;
  limit = std::min(limit, gpu::kMaxBatchSteps);
  const int64_t blocks = std::min(gpu::blocks_for(n), step_wave);
  const bool together = steps_go_together(limit);
  // The cooperative steps measure the bars themselves: one launch fewer a triangulation.
  gpu::StepsMeasure measure;
  if (!(lagged && scale_lagged_ok)) {
    if (together)
      measure = measure_in_steps();
    else
      measure_bars(false);
  }
  // The bars' room, sized by launch_repair_and_bars; their count is on the device.
  if (behind_repair != nullptr) measure.bar_count = totals.data();
  if (force_sum == ForceSum::kAtomic) {
    scattered.resize(2 * n);
    MESHD_CUDA_CHECK(cudaMemsetAsync(scattered.data(), 0, 2 * n * sizeof(double), stream));
    gpu::launch_scatter_bar_forces(p.span(), bars.span(), size.span(), uniform, scale.data(),
                                   scattered.span(), stream);
  } else {
    scattered.resize(0);
  }
  // Twice the blocks' partials: the cooperative steps alternate between the two halves.
  step_partial.resize(2 * blocks);
  gpu::StepBatch& b = *h_batch.get();
  gpu::MoveArgs& a = b.args;
  a.p = p.span();
  a.p_next = p_next.span();
  a.p_old = p_old.span();
  a.velocity = velocity.span();
  a.on_boundary = on_boundary.span();
  a.clearance = clearance.span();
  a.clear = clear;
  a.csr_offset = csr_offset.span();
  a.csr_entry = csr_entry.span();
  a.csr_other = csr_other.span();
  a.size = size.span();
  a.uniform = uniform;
  a.nested_index = nested_index;
  a.scattered = scattered.span();
  a.scale = scale.data();
  a.fd = fd;
  a.nfix = nfix;
  a.h0 = problem->h0;
  a.deltat = prm.deltat;
  a.momentum = prm.momentum;
  a.geps = prm.geps * problem->h0;
  a.deps = prm.deps * problem->h0;
  a.near_boundary = kNearBoundaryRelative * problem->h0;
  a.partial = {step_partial.data(), blocks};
  b.next_scale = lagged ? scale.data() : nullptr;
  b.fscale = prm.fscale;
  b.rule = rule;
  b.first_iteration = first_iteration;
  b.limit = limit;
  b.count = 0;
  constexpr size_t kHead = offsetof(gpu::StepBatch, results);
  // Pinned memory, written only after the last run's copies finished (run_steps syncs). The
  // cooperative steps take it with their launch.
  const auto copy_head = [&] {
    MESHD_CUDA_CHECK(cudaMemcpyAsync(batch.data(), &b, kHead, cudaMemcpyHostToDevice, stream));
  };
  if (together) {
    // The batch ends in h_batch itself: no copy back either.
    gpu::launch_steps_together(b, &b, measure, blocks, stream, behind_repair);
  } else {
    copy_head();
    if (step_graph && limit > 1) {
      step_graph->launch(stream);
    } else {
      gpu::launch_move_nodes(batch.data(), step_wave, stream);
      gpu::launch_finish_step(batch.data(), nullptr, stream);
    }
    constexpr size_t kCount = offsetof(gpu::StepBatch, count);
    MESHD_CUDA_CHECK(cudaMemcpyAsync(
        reinterpret_cast<char*>(&b) + kCount, reinterpret_cast<const char*>(batch.data()) + kCount,
        kHead - kCount + limit * sizeof(StepResult), cudaMemcpyDeviceToHost, stream));
  }
  return lagged;
}

int GpuEngine::Impl::end_steps(bool lagged) {
  const gpu::StepBatch& b = *h_batch.get();
  scale_lagged_ok = lagged && b.count > 0;
  // The device swapped the positions after each step.
  if (b.count % 2 == 1) std::swap(p, p_next);
  return b.count;
}

void GpuEngine::Impl::steps_until(const StepRule& rule, int first_iteration, int limit,
                                  std::vector<StepResult>& steps, int ran) {
  StepRule batch_rule = rule;  // its settling carried from batch to batch
  for (int done = 0; done < limit; ran = 0) {
    if (ran == 0) ran = run_steps(batch_rule, first_iteration + done, limit - done);
    const StepResult* results = h_batch.get()->results;
    steps.insert(steps.end(), results, results + ran);
    done += ran;
    for (int k = 0; k < ran; ++k)
      batch_rule.settling = rule.settle(batch_rule.settling, results[k]);
    if (rule.stops(steps.back(), first_iteration + done - 1, batch_rule.settling)) return;
  }
}

}  // namespace meshd
