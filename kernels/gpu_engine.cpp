#include "kernels/gpu_engine.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "core/delaunay/delaunay.h"
#include "core/distmesh/optimize_worst.h"
#include "kernels/gpu_engine_impl.h"
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"

namespace meshd {
namespace {

// Whether an engine switch named by the environment variable is on: on unless it is "0".
bool on_unless_zero(const char* variable) {
  const char* value = std::getenv(variable);
  return value == nullptr || std::string(value) != "0";
}

}  // namespace

// ---- Engine interface ---------------------------------------------------------------------------

int64_t GpuEngine::device_allocations() { return gpu::AllocationStats::mallocs().load(); }

GpuEngine::GpuEngine(int device) : impl_((gpu::checked_device(device), std::make_unique<Impl>())) {
  impl_->device = device;
  impl_->use_device();
  MESHD_CUDA_CHECK(cudaStreamCreateWithFlags(&impl_->stream, cudaStreamNonBlocking));
  impl_->step_wave = gpu::move_nodes_wave(device);
  set_steps_together(true);
  impl_->batch.resize(1);
  impl_->flip_batch.resize(1);
  MESHD_CUDA_CHECK(
      cudaMemsetAsync(impl_->flip_batch.data(), 0, sizeof(gpu::FlipBatch), impl_->stream));
  impl_->last_block_ticket.resize(1);
  MESHD_CUDA_CHECK(
      cudaMemsetAsync(impl_->last_block_ticket.data(), 0, sizeof(unsigned), impl_->stream));
  // compute-sanitizer's racecheck crashes on graphs with conditional nodes: the variable runs the
  // same kernels launched one by one under it.
  set_step_graph(on_unless_zero("MESHD_GPU_STEP_GRAPH"));
  // 0 makes a small job's steps wait for its retriangulation's outcome (for comparisons: the same
  // bits, bench/RESULTS.md).
  set_steps_behind_repairs(on_unless_zero("MESHD_GPU_STEPS_BEHIND_REPAIRS"));
}

GpuEngine::~GpuEngine() {
  if (impl_ && impl_->stream) {
    cudaSetDevice(impl_->device);
    // The buffers are freed below: whatever the stream still holds must finish first.
    cudaStreamSynchronize(impl_->stream);
    cudaStreamDestroy(impl_->stream);
  }
}

int GpuEngine::device() const { return impl_->device; }
int64_t GpuEngine::node_count() const { return impl_->n; }

int64_t GpuEngine::initialize(const CompiledProblem& problem) {
  Impl& s = *impl_;
  s.use_device();
  s.load_problem(problem);
  const double geps = problem.params.geps * problem.h0;
  const InitialGrid grid = make_initial_grid(problem.bbox, problem.h0);
  const int64_t total = grid.nx * grid.ny;
  s.grid_size.resize(total);
  s.h_min_bits.resize(1);
  MESHD_CUDA_CHECK(
      cudaMemsetAsync(s.h_min_bits.data(), 0xff, sizeof(unsigned long long), s.stream));
  gpu::launch_classify_grid(grid, s.fd, s.fh, geps, s.grid_size.span(), s.h_min_bits.data(),
                            s.stream);
  s.flags.resize(total);
  gpu::launch_flag_grid(grid, s.grid_size.span(), s.h_min_bits.data(), problem.seed, s.fixed.span(),
                        s.flags.span(), s.stream);
  s.position.resize(total);
  gpu::exclusive_scan(s.flags.data(), s.position.data(), total, s.temp, s.stream);
  const int64_t kept = gpu::scan_total(s.position.data(), s.flags.data(), total, s.stream);
  s.n = s.nfix + kept;
  s.p.resize(s.n);
  if (s.nfix > 0)
    MESHD_CUDA_CHECK(cudaMemcpyAsync(s.p.data(), s.fixed.data(), s.nfix * sizeof(Vec2),
                                     cudaMemcpyDeviceToDevice, s.stream));
  gpu::launch_scatter_grid(grid, s.flags.span(), s.position.span(), s.p.span(), s.nfix, s.stream);
  s.reset_node_state();
  s.prepare(grid);
  return s.n;
}

int64_t GpuEngine::load_points(const CompiledProblem& problem, const std::vector<Vec2>& points) {
  Impl& s = *impl_;
  s.use_device();
  s.load_problem(problem);
  s.n = static_cast<int64_t>(points.size());
  s.p.upload(points.data(), points.size(), s.stream);
  s.reset_node_state();
  // Triangles prepared for other points (a refinement's split ones) no longer fit.
  s.prepared = false;
  return s.n;
}

int64_t GpuEngine::refine(const CompiledProblem& finer) {
  Impl& s = *impl_;
  s.use_device();
  s.load_problem(finer);
  const gpu::RefineRule rule{s.fd, s.fh, finer.h0, finer.params.deps * finer.h0, s.nfix};
  s.n = gpu::refine_level(rule, s.keep.span(), s.p, s.tris, s.nbrs, s.refine_scratch, s.temp,
                          s.stream);
  s.reset_node_state();
  // The split triangles start the next full triangulation. They have gaps where the coarse
  // level's repairs dropped turned-over slivers, pockets along the hull where a boundary midpoint
  // was projected out of it, and folds where one was projected past a neighbour: completed.
  s.prepare_completion();
  return s.n;
}

TopologyStats GpuEngine::retriangulate(bool full) {
  Impl& s = *impl_;
  s.use_device();
  if (!full && s.have_triangulation && s.one_block_retriangulation()) {
    s.launch_repair_and_bars();
    s.sync();
    return s.end_one_block_repair();
  }
  TopologyStats stats;
  stats.full = full || !s.have_triangulation;
  if (stats.full && s.prepared) {
    stats.flips = s.flip_prepared();
    if (stats.flips < 0) {
      // The survivors of a node removal come from an older triangulation: one may have turned.
      int64_t dropped = 0;
      stats.flips = s.repair_folds_too(dropped, stats.folds_refilled);
    }
    if (stats.flips >= 0) {
      s.have_triangulation = true;
      const TopologyStats sizes = s.filter_and_bars();
      stats.triangles = sizes.triangles;
      stats.bars = sizes.bars;
      return stats;
    }
    stats.flips = 0;
    stats.repair_failed = true;
  } else if (stats.full && s.have_triangulation) {
    // The node set is the same as at the last triangulation: the loop asks for a full one to
    // close the gaps of dropped slivers. Repair, and rebuild only if a gap is really there.
    int64_t dropped = 0;
    int64_t flips = s.repair_folds_too(dropped, stats.folds_refilled);
    if (flips >= 0 && !s.covers_hull()) {
      // Close the gaps with CGAL on their boundary points alone, then flip again.
      flips = s.prepare_completion() ? s.flip_prepared() : -1;
    }
    if (flips >= 0) {
      stats.flips = flips;
      const TopologyStats sizes = s.filter_and_bars();
      stats.triangles = sizes.triangles;
      stats.bars = sizes.bars;
      return stats;
    }
    stats.repair_failed = true;
  } else if (!stats.full) {
    const int64_t flips = s.repair_folds_too(stats.dropped, stats.folds_refilled);
    if (flips < 0) {
      stats.full = true;
      stats.repair_failed = true;
    } else {
      stats.flips = flips;
    }
  }
  return s.end_retriangulation(stats, false);
}

int64_t GpuEngine::remove_crowded_points(int64_t max_removed) {
  Impl& s = *impl_;
  s.use_device();
  s.measure_bars(true);
  s.flags.resize(s.n);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.flags.data(), 1, s.n, s.stream));
  gpu::launch_mark_crowded(s.bars.span(), s.length.span(), s.size.span(), s.scale.data(), s.nfix,
                           s.flags.span(), s.stream);
  return s.compact_nodes(max_removed);
}

int64_t GpuEngine::remove_boundary_slivers(const CompiledProblem& problem, int64_t max_removed) {
  Impl& s = *impl_;
  s.use_device();
  // Found where the points and triangles are: reading a million of each to the host and back
  // cost more than the clean-up's relaxation.
  s.flags.resize(s.n);
  MESHD_CUDA_CHECK(cudaMemsetAsync(s.flags.data(), 1, s.n, s.stream));
  gpu::launch_mark_boundary_slivers(s.p.span(), s.tris.span(), s.keep.span(), s.fd,
                                    problem.params.geps * problem.h0, s.nfix, s.flags.span(),
                                    s.stream);
  return s.compact_nodes(max_removed);
}

void GpuEngine::remove_points(const std::vector<int32_t>& indices) {
  Impl& s = *impl_;
  s.use_device();
  std::vector<uint8_t> keep(s.n, 1);
  for (int32_t i : indices)
    if (i >= s.nfix && i < s.n) keep[i] = 0;
  s.flags.upload(keep.data(), keep.size(), s.stream);
  s.compact_nodes(kRemoveAny);
}

StepResult GpuEngine::move_points() {
  Impl& s = *impl_;
  s.use_device();
  s.run_steps(StepRule{}, 1, 1);  // one step: the rule does not matter
  return s.h_batch.get()->results[0];
}

void GpuEngine::move_points_until(const StepRule& rule, int first_iteration, int limit,
                                  std::vector<StepResult>& steps) {
  Impl& s = *impl_;
  s.use_device();
  s.steps_until(rule, first_iteration, limit, steps, 0);
}

std::optional<TopologyStats> GpuEngine::retriangulate_and_move(const StepRule& rule,
                                                               int first_iteration, int limit,
                                                               std::vector<StepResult>& steps) {
  Impl& s = *impl_;
  s.use_device();
  if (!s.steps_behind_repairs || !s.have_triangulation || !s.one_block_retriangulation() ||
      !s.steps_go_together(limit))
    return std::nullopt;
  s.launch_repair_and_bars();
  const bool lagged = s.launch_steps(rule, first_iteration, limit, s.counters.data());
  s.sync();  // the repair's counters, the bars' totals and the steps' batch
  const TopologyStats stats = s.end_one_block_repair();
  const int ran = s.end_steps(lagged);
  if (ran > 0) {
    ++s.steps_behind_repair_batches;
    s.size_measure(false);  // from the bars' room to their count
  }
  // Where the repair did not settle on the device, the steps did not run: they follow its rest.
  s.steps_until(rule, first_iteration, limit, steps, ran);
  return stats;
}

int GpuEngine::preferred_batch() const { return impl_->step_graph ? gpu::kMaxBatchSteps : 1; }

void GpuEngine::set_step_graph(bool on) {
  Impl& s = *impl_;
  s.use_device();
  if (!on) {
    s.step_graph.reset();
    s.flip_loop_blocks = 0;
  } else if (!s.step_graph) {
    gpu::StepBatch* batch = s.batch.data();
    const int64_t wave = s.step_wave;
    s.step_graph = std::make_unique<gpu::LoopGraph>(
        [&](const cudaGraphConditionalHandle& more, cudaStream_t stream) {
          gpu::launch_move_nodes(batch, wave, stream);
          gpu::launch_finish_step(batch, &more, stream);
        },
        s.stream);
    s.flip_loop_blocks = gpu::flip_loop_blocks(s.device);
  }
}

void GpuEngine::read_points(std::vector<Vec2>& points) {
  Impl& s = *impl_;
  s.use_device();
  points.resize(s.n);
  s.p.download(points.data(), s.stream);
  s.sync();
}

Triangulation GpuEngine::delaunay(const std::vector<Vec2>& points, DelaunayTiming* timing) {
  Impl& s = *impl_;
  s.use_device();
  s.n = static_cast<int64_t>(points.size());
  s.nfix = 0;
  s.p.upload(points.data(), points.size(), s.stream);
  s.sync();
  const auto t0 = std::chrono::steady_clock::now();
  s.full_triangulation();
  s.sync();
  const auto t1 = std::chrono::steady_clock::now();
  Triangulation out;
  out.triangles.resize(s.tris.size());
  out.neighbors.resize(s.nbrs.size());
  static_assert(sizeof(Tri) == sizeof(std::array<int32_t, 3>));
  s.tris.download(reinterpret_cast<Tri*>(out.triangles.data()), s.stream);
  s.nbrs.download(reinterpret_cast<Tri*>(out.neighbors.data()), s.stream);
  s.sync();
  s.have_triangulation = false;
  if (timing != nullptr) {
    timing->seconds = std::chrono::duration<double>(t1 - t0).count();
    timing->insertion_steps = s.last_insertion.insertion_steps;
    timing->flip_steps = s.last_insertion.flip_steps;
  }
  return out;
}

void GpuEngine::read_triangles(std::vector<std::array<int32_t, 3>>& triangles) {
  Impl& s = *impl_;
  s.use_device();
  // Compacted on the device: at a million triangles the host loop over all of them cost more
  // than the copy.
  const int64_t kept = s.compact_alive_triangles(s.keep);
  triangles.resize(kept);
  static_assert(sizeof(Tri) == sizeof(std::array<int32_t, 3>));
  s.tris_tmp.download(reinterpret_cast<Tri*>(triangles.data()), s.stream);
  s.sync();
}

void GpuEngine::read_mesh(MeshCopy& copy) {
  Impl& s = *impl_;
  s.use_device();
  read_points(copy.points);
  // read_triangles leaves the kept triangles and their links in tris_tmp and nbrs_tmp.
  read_triangles(copy.triangles);
  s.finish.tris.assign(s.tris_tmp, s.stream);
  gpu::MeshFacts facts =
      gpu::find_mesh_facts(s.p.span(), s.tris_tmp.span(), s.nbrs_tmp.span(), kOptimizeBelowQuality,
                           s.nfix, s.finish, s.temp, s.stream);
  copy.boundary = std::move(facts.boundary);
  copy.below = std::move(facts.below);
  copy.tidy = s.copy_tidy = facts.tidy;
  copy.none_trapped = facts.none_trapped;
}

QualityStats GpuEngine::measure_quality(const Mesh& mesh, bool moved) {
  Impl& s = *impl_;
  // An untidy copy was renumbered on the host: its triangles are no longer the device's.
  if (!s.copy_tidy || static_cast<int64_t>(mesh.points.size()) != s.n ||
      mesh.triangles.size() != s.finish.tris.size())
    return Engine::measure_quality(mesh, moved);
  s.use_device();
  gpu::DeviceSpan<const Vec2> points = s.p.span();
  if (moved) {
    s.p_next.upload(mesh.points.data(), mesh.points.size(), s.stream);
    points = s.p_next.span();
  }
  return gpu::measure_quality(points, s.finish.tris.span(), s.finish, s.stream);
}

void GpuEngine::set_force_sum(ForceSum mode) { impl_->force_sum = mode; }
void GpuEngine::set_flip_rounds_per_launch(int rounds) { impl_->flip_rounds_per_launch = rounds; }
void GpuEngine::set_flip_tail_items(int items) { impl_->flip_tail_items = items; }
void GpuEngine::set_steps_together(bool on) {
  // Every batch has at most step_wave blocks.
  impl_->steps_together = on && gpu::steps_together_fit(impl_->device, impl_->step_wave);
}

void GpuEngine::set_replayed_triangles(int64_t triangles) { impl_->replayed_triangles = triangles; }
void GpuEngine::set_one_block_topology(bool on) { impl_->one_block_topology = on; }

void GpuEngine::set_steps_behind_repairs(bool on) { impl_->steps_behind_repairs = on; }

int64_t GpuEngine::steps_behind_repair_batches() const {
  return impl_->steps_behind_repair_batches;
}
int64_t GpuEngine::bars_replays() const { return impl_->bars_graph.replays(); }
int64_t GpuEngine::one_read_retriangulations() const { return impl_->one_read_retriangulations; }
void GpuEngine::set_lagged_scale(bool on) { impl_->lagged_scale = on; }

void GpuEngine::warm_up() {
  Problem disk;
  disk.geometry = Shape{Circle{{0.0, 0.0}, 1.0}, "", ""};
  disk.h0 = 0.1;
  const CompiledProblem compiled = compile_problem(disk);
  initialize(compiled);
  retriangulate(true);
  for (int i = 0; i < 3; ++i) move_points();
  retriangulate(false);
  remove_crowded_points(kRemoveAny);
}

}  // namespace meshd
