#include "kernels/gpu_engine.h"

#include <cuda.h>
#include <cuda_runtime.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>

#include "core/common/error.h"
#include "core/delaunay/delaunay.h"
#include "core/delaunay/exact_predicates.h"
#include "core/distmesh/optimize_worst.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "kernels/complete_gaps.h"
#include "kernels/device_buffer.h"
#include "kernels/finish_mesh.h"
#include "kernels/flip_round.h"
#include "kernels/keep_triangles.h"
#include "kernels/lattice_triangulation.h"
#include "kernels/launch.h"
#include "kernels/loop_graph.h"
#include "kernels/pinned_value.h"
#include "kernels/point_insertion.h"
#include "kernels/refine_level.h"
#include "kernels/replay_graph.h"
#include "kernels/scan.h"

namespace meshd {

using gpu::Bar;
using gpu::BarSums;
using gpu::DeviceBuffer;
using gpu::PinnedValue;
using gpu::StepSums;
using gpu::Tri;

namespace {

// Undecided in-circle tests a round may hand to the host; more means a rebuild.
constexpr int32_t kMaxUndecided = 4096;
// Flip rounds launched one by one (without the device's loop) between two reads of the counters.
constexpr int kRoundsPerBatch = 8;
// A repair that needs more batches of rounds than this (kRoundsPerBatch rounds each, or in the
// loop up to flip_rounds_per_launch) is pathological: rebuild instead.
constexpr int kMaxFlipLaunches = 25;
// Triangulations up to this size get their bars through one graph (filter_and_bars).
constexpr int64_t kReplayedTriangles = int64_t{1} << 18;

}  // namespace

int gpu_device_count() {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

void share_gpus_among_engines() {
  setenv("CUDA_MODULE_LOADING", "EAGER", /*overwrite=*/0);
  const int devices = gpu_device_count();
  for (int d = 0; d < devices; ++d) {
    MESHD_CUDA_CHECK(cudaSetDevice(d));
    MESHD_CUDA_CHECK(cudaSetDeviceFlags(cudaDeviceScheduleYield));
  }
}

bool gpu_kernels_load_eagerly() {
  // A driver call: the runtime does not report the loading mode.
  using LoadingMode = CUresult (*)(CUmoduleLoadingMode*);
  void* entry = nullptr;
  cudaDriverEntryPointQueryResult found{};
  MESHD_CUDA_CHECK(cudaGetDriverEntryPointByVersion("cuModuleGetLoadingMode", &entry, 12000,
                                                    cudaEnableDefault, &found));
  CUmoduleLoadingMode mode{};
  return found == cudaDriverEntryPointSuccess &&
         reinterpret_cast<LoadingMode>(entry)(&mode) == CUDA_SUCCESS &&
         mode == CU_MODULE_EAGER_LOADING;
}

bool gpu_waits_yield(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  unsigned flags = 0;
  MESHD_CUDA_CHECK(cudaGetDeviceFlags(&flags));
  return (flags & cudaDeviceScheduleMask) == cudaDeviceScheduleYield;
}

int64_t gpu_memory_in_use(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  size_t free = 0, total = 0;
  MESHD_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  return static_cast<int64_t>(total - free);
}

std::string gpu_device_name(int device) {
  cudaDeviceProp prop{};
  MESHD_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  return prop.name;
}

double measure_copy_bandwidth(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  constexpr size_t kBytes = size_t{512} << 20;
  DeviceBuffer<uint8_t> a, b;
  a.resize(kBytes);
  b.resize(kBytes);
  MESHD_CUDA_CHECK(cudaMemset(a.data(), 1, kBytes));
  cudaEvent_t start, stop;
  MESHD_CUDA_CHECK(cudaEventCreate(&start));
  MESHD_CUDA_CHECK(cudaEventCreate(&stop));
  std::vector<float> ms;
  for (int i = 0; i < 11; ++i) {
    MESHD_CUDA_CHECK(cudaEventRecord(start));
    MESHD_CUDA_CHECK(cudaMemcpy(b.data(), a.data(), kBytes, cudaMemcpyDeviceToDevice));
    MESHD_CUDA_CHECK(cudaEventRecord(stop));
    MESHD_CUDA_CHECK(cudaEventSynchronize(stop));
    float t = 0;
    MESHD_CUDA_CHECK(cudaEventElapsedTime(&t, start, stop));
    if (i > 0) ms.push_back(t);
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  std::sort(ms.begin(), ms.end());
  return 2.0 * kBytes / (ms[ms.size() / 2] * 1e-3) / 1e9;
}

int64_t GpuEngine::device_allocations() { return gpu::AllocationStats::mallocs().load(); }

// ---- State --------------------------------------------------------------------------------------

struct GpuEngine::Impl {
  int device = 0;
  cudaStream_t stream = nullptr;
  const CompiledProblem* problem = nullptr;

  // The programs, on the device.
  DeviceBuffer<Instruction> geometry_code, size_code;
  DeviceBuffer<double> geometry_params, size_params;
  DeviceBuffer<BvhNode> geometry_nodes, size_nodes;
  DeviceBuffer<float> geometry_samples, size_samples;
  DeviceBuffer<SizeTermCode> size_terms;
  ProgramView fd{};
  SizeView fh{};
  bool uniform = true;
  bool nested_index = false;  // nests_indexed_unions (compile.h)

  // Nodes (fixed first).
  int64_t n = 0, nfix = 0;
  DeviceBuffer<Vec2> p, p_next, p_old, velocity, fixed;
  DeviceBuffer<uint8_t> on_boundary;
  DeviceBuffer<float> clearance;  // clearance.cuh
  ClearanceRule clear{};

  // Triangulation: all Delaunay triangles, their neighbours, the kept flags, the bars and CSR.
  bool have_triangulation = false;
  // tris and nbrs hold the initial points' triangulation by construction, not yet flipped to
  // Delaunay nor filtered: the next full triangulation starts from it instead of CGAL.
  bool prepared = false;
  bool prepared_checked = false;   // its triangles' orientation is known to be right
  bool completion_failed = false;  // the last completion's checks failed: CGAL instead
  DeviceBuffer<Tri> tris, nbrs, tris_tmp, nbrs_tmp;
  DeviceBuffer<uint8_t> keep, flags;
  DeviceBuffer<int32_t> vote, flipped_round, partner, position, count, next;
  DeviceBuffer<int64_t> totals;  // scan totals, read through pinned memory at the next wait
  PinnedValue<std::array<int64_t, 2>> h_totals;
  PinnedValue<int64_t> h_live;            // filter_and_bars' triangles, for the device's totals[2]
  gpu::ReplayGraph bars_graph;            // filter_and_bars
  int64_t one_read_retriangulations = 0;  // end_one_block_repair's that found the bars built
  // Steps launched behind a small retriangulation's repair (GpuEngine::retriangulate_and_move),
  // and the batches that ran there.
  bool steps_behind_repairs = true;
  int64_t steps_behind_repair_batches = 0;
  int64_t replayed_triangles = kReplayedTriangles;
  // A small triangulation's repair and bars in one block's launch each (kOneBlockRows).
  bool one_block_topology = true;
  // Changes with every argument that bars_graph's launches take by value: a new problem (or
  // level) and a new node set.
  uint64_t epoch = 0;
  DeviceBuffer<int32_t> undecided, decided;  // in-circle tests for the host, and its verdicts
  DeviceBuffer<gpu::InCircleTest> in_circle_tests;  // the undecided tests' points
  gpu::FlipLists flip_lists;
  DeviceBuffer<gpu::FlipBatch> flip_batch;  // one
  int64_t flip_loop_blocks = 0;  // the rounds' cooperative loop (0: rounds launched one by one)
  int32_t flip_tail_items = gpu::kFlipTailItems;
  int32_t flip_rounds_per_launch = gpu::kLoopFlipRounds;
  DeviceBuffer<Bar> bars;
  DeviceBuffer<double> length, size, scale, grid_size, scattered;
  ForceSum force_sum = ForceSum::kGather;
  bool lagged_scale = true;
  bool scale_lagged_ok = false;  // scale holds the last step's measure of the current bars
  DeviceBuffer<int32_t> csr_offset, csr_entry, csr_other, degree;
  DeviceBuffer<BarSums> bar_partial;
  // The blocks done of a kernel whose last block finishes its work (measure_bars, filter_and_bars);
  // 0 between launches, which run one after the other on the stream.
  DeviceBuffer<unsigned> last_block_ticket;
  DeviceBuffer<StepSums> step_partial;
  int64_t step_wave = 1;                       // move_nodes_wave
  DeviceBuffer<gpu::StepBatch> batch;          // one, for the step graph
  std::unique_ptr<gpu::LoopGraph> step_graph;  // null: the step's kernels launched one by one
  // A batch's steps in one cooperative launch rather than the graph's loop, where they fit.
  bool steps_together = false;
  DeviceBuffer<gpu::TopologyCounters> counters;
  DeviceBuffer<unsigned long long> h_min_bits;
  DeviceBuffer<uint8_t> temp;
  gpu::RefineScratch refine_scratch;
  gpu::GapScratch gaps;
  gpu::LatticeScratch lattice;
  gpu::InsertionScratch insertion;
  gpu::InsertionCounts last_insertion;
  gpu::FinishScratch finish;
  // The last read_mesh's copy of this job was tidy: its triangles (kept in finish) are the
  // result's.
  bool copy_tidy = false;
  PinnedValue<gpu::StepBatch> h_batch;
  PinnedValue<gpu::TopologyCounters> h_counters;

  void sync() { MESHD_CUDA_CHECK(cudaStreamSynchronize(stream)); }
  void use_device() { MESHD_CUDA_CHECK(cudaSetDevice(device)); }

  void load_problem(const CompiledProblem& prob) {
    problem = &prob;
    ++epoch;
    copy_tidy = false;
    geometry_code.upload(prob.geometry.code.data(), prob.geometry.code.size(), stream);
    geometry_params.upload(prob.geometry.params.data(), prob.geometry.params.size(), stream);
    size_code.upload(prob.size.shapes.code.data(), prob.size.shapes.code.size(), stream);
    size_params.upload(prob.size.shapes.params.data(), prob.size.shapes.params.size(), stream);
    geometry_nodes.upload(prob.geometry.nodes.data(), prob.geometry.nodes.size(), stream);
    size_nodes.upload(prob.size.shapes.nodes.data(), prob.size.shapes.nodes.size(), stream);
    geometry_samples.upload(prob.geometry.samples.data(), prob.geometry.samples.size(), stream);
    size_samples.upload(prob.size.shapes.samples.data(), prob.size.shapes.samples.size(), stream);
    size_terms.upload(prob.size.terms.data(), prob.size.terms.size(), stream);
    fd = {geometry_code.data(), static_cast<uint32_t>(prob.geometry.code.size()),
          geometry_params.data(), geometry_nodes.data(), geometry_samples.data()};
    fh = {{size_code.data(), static_cast<uint32_t>(prob.size.shapes.code.size()),
           size_params.data(), size_nodes.data(), size_samples.data()},
          size_terms.data(),
          static_cast<uint32_t>(prob.size.terms.size())};
    uniform = prob.size.uniform();
    nested_index = nests_indexed_unions(prob.geometry);
    nfix = static_cast<int64_t>(prob.fixed_points.size());
    fixed.upload(prob.fixed_points.data(), prob.fixed_points.size(), stream);
  }

  // After the node set changed: no momentum, no triangulation, drift "infinite".
  void reset_node_state() {
    ++epoch;
    p_next.resize(n);
    p_old.resize(n);
    velocity.resize(n);
    on_boundary.resize(n);
    clearance.resize(n);
    if (n > 0) {
      MESHD_CUDA_CHECK(cudaMemsetAsync(p_old.data(), 0x7f, n * sizeof(Vec2), stream));  // ~1e306
      MESHD_CUDA_CHECK(cudaMemsetAsync(velocity.data(), 0, n * sizeof(Vec2), stream));
      MESHD_CUDA_CHECK(cudaMemsetAsync(on_boundary.data(), 0, n, stream));
      // Zero: unknown, evaluated at the next step.
      MESHD_CUDA_CHECK(cudaMemsetAsync(clearance.data(), 0, n * sizeof(float), stream));
    }
    clear = ClearanceRule::make(problem->lipschitz, problem->params.geps * problem->h0,
                                kNearBoundaryRelative * problem->h0, problem->h0);
    // Fixed nodes never move: classify them once, on the host.
    std::vector<uint8_t> fixed_boundary(nfix);
    const double near = kNearBoundaryRelative * problem->h0;
    for (int64_t f = 0; f < nfix; ++f)
      fixed_boundary[f] = eval_sdf(problem->geometry.view(), problem->fixed_points[f]) >= -near;
    if (nfix > 0)
      MESHD_CUDA_CHECK(cudaMemcpyAsync(on_boundary.data(), fixed_boundary.data(), nfix,
                                       cudaMemcpyHostToDevice, stream));
    have_triangulation = false;
    prepared = false;
    scale_lagged_ok = false;
    bars.resize(0);
    sync();  // fixed_boundary is a stack buffer
  }

  // Keeps the nodes with flags[i] = 1, in order. Returns how many went; with none, or more than
  // max_removed, leaves the nodes and their triangulation as they are (and returns 0).
  int64_t compact_nodes(int64_t max_removed) {
    position.resize(n);
    gpu::exclusive_scan(flags.data(), position.data(), n, temp, stream);
    const int64_t kept = gpu::scan_total(position.data(), flags.data(), n, stream);
    if (kept == n || n - kept > max_removed) return 0;
    // The triangles untouched by the removal survive, renumbered, with their links: the next
    // full triangulation completes them (complete_gaps.h) instead of starting over.
    bool survived = false;
    if (have_triangulation) {
      // keep serves as scratch: the next triangulation sets it again.
      keep.resize(tris.size());
      gpu::launch_surviving_triangles(tris.span(), flags.span(), keep.span(), stream);
      survived = gpu::keep_triangles(keep.span(), tris, nbrs, {count, tris_tmp, nbrs_tmp}, temp,
                                     stream) > 0;
      gpu::launch_renumber_vertices(tris.span(), position.span(), stream);
    }
    gpu::launch_compact_points(p.span(), flags.span(), position.span(), p_next.span(), stream);
    std::swap(p, p_next);
    const int64_t removed = n - kept;
    n = kept;
    p.resize(n);
    reset_node_state();
    if (survived) prepare_completion();
    return removed;
  }

  // Copies the triangles with alive[t] into tris_tmp, in order, and their links into nbrs_tmp
  // (-1 where the neighbour is not alive). Returns how many. `count` holds the scan.
  int64_t compact_alive_triangles(const DeviceBuffer<uint8_t>& alive) {
    const int64_t m = static_cast<int64_t>(tris.size());
    count.resize(m);
    gpu::exclusive_scan(alive.data(), count.data(), m, temp, stream);
    const int64_t kept = gpu::scan_total(count.data(), alive.data(), m, stream);
    tris_tmp.resize(kept);
    nbrs_tmp.resize(kept);
    gpu::launch_compact_triangles(tris.span(), nbrs.span(), alive.span(), count.span(),
                                  tris_tmp.span(), nbrs_tmp.span(), stream);
    return kept;
  }

  // Completes tris and nbrs (triangles of some of the current nodes, linked) for the next full
  // triangulation (complete_gaps.h); the nodes may have moved since those triangles were made,
  // so the flips check orientations first. Returns false when the completion failed: then the
  // next full triangulation starts over with CGAL, and reports a fallback.
  bool prepare_completion() {
    // A survivor or a split triangle may have turned over: cut out first, the fold then filled
    // with the gaps.
    const bool folded = gpu::cut_folds(p.span(), tris, nbrs, gaps, temp, stream);
    prepared = (!folded && covers_hull()) ||
               gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream) ||
               complete_from_domain_triangles();
    prepared_checked = false;
    completion_failed = !prepared;
    return prepared;
  }
  // The completion once the tries of complete_gaps failed. Triangles outside the domain, flat
  // ones between the hull and a straight side above all, can come to overlap as their nodes move
  // without any of them turning over, and their walls then cross; eroding the triangles next to
  // the gaps need not reach them. The domain's own triangles (the centroid filter's) bound the
  // gaps instead, as on the host's refinement: a last resort, since every node on the domain's
  // boundary then bounds a gap (0.9 s a completion on a coastline of 640k nodes).
  bool complete_from_domain_triangles() {
    keep.resize(tris.size());  // scratch: the next triangulation sets it again
    gpu::launch_centroid_filter(p.span(), clearance.span(), clear, tris.span(), fd, nested_index,
                                problem->params.geps * problem->h0, keep.span(), nullptr, stream);
    gpu::keep_triangles(keep.span(), tris, nbrs, {position, tris_tmp, nbrs_tmp}, temp, stream);
    return gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream);
  }

  // Step 4. The step itself needs only the sizes of a graded field; density control needs the
  // lengths and sizes of every bar.
  void measure_bars(bool for_density_control) {
    size_measure(for_density_control);
    gpu::launch_measure_bars(
        p.span(), bars.span(), fh, uniform, length.span(), size.span(),
        {bar_partial.data(), last_block_ticket.data(), problem->params.fscale, scale.data()},
        stream);
  }
  // measure_bars(false) as the cooperative steps' first work: the arguments for their launch.
  gpu::StepsMeasure measure_in_steps() {
    return {.on = true,
            .uniform = uniform,
            .blocks = size_measure(false),
            .bars = bars.span(),
            .fh = fh,
            .size = size.span(),
            .partial = bar_partial.data()};
  }
  // Sizes a measure's buffers; returns its blocks.
  int64_t size_measure(bool for_density_control) {
    const int64_t nb = static_cast<int64_t>(bars.size());
    const bool store_size = for_density_control || !uniform;
    length.resize(for_density_control ? nb : 0);
    size.resize(store_size ? nb : 0);
    const int64_t blocks = gpu::nonempty_reduce_blocks_for(nb);
    bar_partial.resize(blocks);
    scale.resize(2);
    return blocks;
  }

  // Runs up to `limit` steps (4, 5, 7, 8) in one launch of the step graph; one, launched
  // directly, when each step needs the host first (the bar measure of the exact scale, the
  // atomic force sums) or without the graph. A graded field's sizes are measured once per
  // topology, at the first step after a triangulation, as the CPU engine does. Returns how many
  // ran; their results are in h_batch.
  int run_steps(const StepRule& rule, int first_iteration, int limit) {
    const bool lagged = launch_steps(rule, first_iteration, limit);
    sync();
    return end_steps(lagged);
  }
  // Whether steps keep the L0 scale of the step before (set_lagged_scale).
  bool lagged_steps() const {
    return lagged_scale && force_sum == ForceSum::kGather && bars.size() > 0;
  }
  // Whether a batch of up to `limit` steps runs in one cooperative launch. A lone step costs less
  // launched directly than through the graph's loop (on an H200 at 1M nodes, a step of the exact
  // scale took 119-130 us through it, 110-122 us directly). A wave of blocks or more (about 100k
  // nodes on an H200) takes the graph's loop: there a step's work hides the loop's launches, and
  // the cooperative kernel, all of a step's code in one, was slower on plate_with_holes at 1M
  // nodes (110 against 104 us a step).
  bool steps_go_together(int limit) const {
    return lagged_steps() && step_graph && std::min(limit, gpu::kMaxBatchSteps) > 1 &&
           steps_together && std::min(gpu::blocks_for(n), step_wave) < step_wave;
  }
  // run_steps' launch; returns whether the steps keep the lagged scale, for end_steps once the
  // host has waited. `behind_repair`: the steps go together (steps_go_together), behind the
  // repair whose counters these are and the bars it leaves, both not read yet
  // (launch_repair_and_bars).
  bool launch_steps(const StepRule& rule, int first_iteration, int limit,
                    const gpu::TopologyCounters* behind_repair = nullptr) {
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
      MESHD_CUDA_CHECK(cudaMemcpyAsync(reinterpret_cast<char*>(&b) + kCount,
                                       reinterpret_cast<const char*>(batch.data()) + kCount,
                                       kHead - kCount + limit * sizeof(StepResult),
                                       cudaMemcpyDeviceToHost, stream));
    }
    return lagged;
  }
  // After the wait for launch_steps: how many steps ran (none behind a repair that did not settle,
  // which leaves the batch as the host set it); their results are in h_batch.
  int end_steps(bool lagged) {
    const gpu::StepBatch& b = *h_batch.get();
    scale_lagged_ok = lagged && b.count > 0;
    // The device swapped the positions after each step.
    if (b.count % 2 == 1) std::swap(p, p_next);
    return b.count;
  }
  // Batches of steps until `limit` ran or the rule stops (GpuEngine::move_points_until), the
  // results appended to `steps`; the first batch's `ran` steps are in h_batch already where not 0.
  void steps_until(const StepRule& rule, int first_iteration, int limit,
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

  // ---- Step 3 ----

  std::vector<Vec2> download_points() {
    std::vector<Vec2> host(n);
    p.download(host.data(), stream);
    sync();
    return host;
  }

  // A triangulation from scratch: the device's point insertion, its hull completed and flipped
  // with exact predicates; CGAL on the host where that fails (a completion's checks).
  void full_triangulation() {
    if (triangulate_on_device()) return;
    const Triangulation dt = delaunay_triangulate(download_points());
    static_assert(sizeof(Tri) == sizeof(std::array<int32_t, 3>));
    tris.upload(reinterpret_cast<const Tri*>(dt.triangles.data()), dt.triangles.size(), stream);
    nbrs.upload(reinterpret_cast<const Tri*>(dt.neighbors.data()), dt.neighbors.size(), stream);
    flipped_round.resize(tris.size());
    MESHD_CUDA_CHECK(cudaMemsetAsync(flipped_round.data(), 0xff,
                                     flipped_round.size() * sizeof(int32_t), stream));
  }

  bool triangulate_on_device() {
    last_insertion = gpu::insert_points(p.span(), tris, nbrs, insertion, temp, stream);
    // Every triangle is counter-clockwise by the insertion's exact predicates, and the gaps' by
    // CGAL's: the flips need no orientation check.
    prepared = covers_hull() || gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream);
    prepared_checked = prepared;
    return prepared && flip_prepared() >= 0;
  }

  // The initial triangulation (lattice_triangulation.h) for the first retriangulate; without
  // it (its completion failed) the first one is built from scratch.
  void prepare(const InitialGrid& grid) {
    prepared = gpu::lattice_triangulation(grid, flags.span(), position.span(), nfix, p.span(), tris,
                                          nbrs, lattice, gaps, temp, stream);
    prepared_checked = prepared;
  }

  // Flips the prepared triangulation to Delaunay. Returns the flips, or -1 when it cannot (a
  // triangle turned over): then the caller triangulates with CGAL.
  int64_t flip_prepared() {
    prepared = false;
    const int64_t m = static_cast<int64_t>(tris.size());
    keep.resize(m);  // every triangle counts: any that turned over calls for a rebuild
    MESHD_CUDA_CHECK(cudaMemsetAsync(keep.data(), 1, m, stream));
    flipped_round.resize(m);
    MESHD_CUDA_CHECK(cudaMemsetAsync(flipped_round.data(), 0xff, m * sizeof(int32_t), stream));
    // No orientation check for the lattice: the host checked every triangle with exact
    // predicates, and flat pockets along lattice lines would leave the device's filter undecided.
    if (prepared_checked) return flip_to_delaunay();
    int64_t dropped = 0;
    return repair(dropped);
  }

  // Whether the triangulation covers the convex hull of all n nodes, as a full one does: a
  // disk (2 n - 2 - h triangles for h edges on its boundary) whose boundary never turns right.
  // After a repair that dropped collapsed slivers this is usually still so, and then the
  // repaired triangulation is the one CGAL would build.
  bool covers_hull() {
    const int64_t m = static_cast<int64_t>(tris.size());
    next.resize(n);
    reset_counters();
    gpu::launch_hull_links(tris.span(), nbrs.span(), next.span(), counters.data(), stream);
    gpu::launch_hull_turns(p.span(), tris.span(), nbrs.span(), next.span(), counters.data(),
                           stream);
    const gpu::TopologyCounters c = read_counters();
    // hull_links counts boundary edges in `candidates`, hull_turns right turns in `fatal`.
    return c.fatal == 0 && m == 2 * n - 2 - c.candidates;
  }

  void reset_counters() {
    counters.resize(1);
    MESHD_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, sizeof(gpu::TopologyCounters), stream));
  }
  const gpu::TopologyCounters& read_counters() {
    MESHD_CUDA_CHECK(cudaMemcpyAsync(h_counters.get(), counters.data(),
                                     sizeof(gpu::TopologyCounters), cudaMemcpyDeviceToHost,
                                     stream));
    sync();
    return *h_counters.get();
  }

  // repair, and where a node crossed an edge (a triangle turned over, which flips cannot undo)
  // the fold cut out and filled (refill_folds.h, here through complete_gaps.h), then flipped.
  // Returns the flips, or -1 when a rebuild is needed; `refilled` tells whether a fold was mended.
  int64_t repair_folds_too(int64_t& dropped, bool& refilled) {
    const int64_t flips = repair(dropped);
    return flips >= 0 ? flips : mend_folds(refilled);
  }
  // After a repair that called for a rebuild: the fold cut out and filled, then flipped.
  int64_t mend_folds(bool& refilled) {
    if (!prepare_completion()) return -1;
    refilled = true;
    return flip_prepared();
  }

  // Whether a partial retriangulation's repair removes its dropped triangles in the same launch,
  // with the filter and the bars behind it before the host reads (flip_round.h's OneBlockRepair).
  bool one_block_retriangulation() const {
    return one_block_topology && gpu::bars_fit_one_block(static_cast<int64_t>(tris.size()), n);
  }
  // A partial retriangulation's repair and its filter and bars (one_block_retriangulation), as
  // repair_folds_too and filter_and_bars with one read where the repair settles on the device
  // (flip_round.h's OneBlockRepair). The bars' launch sends the repair's counters and its totals
  // to the host's memory; end_one_block_repair reads them after the host's wait.
  void launch_repair_and_bars() {
    const auto m = static_cast<int64_t>(tris.size());
    size_filter(m);
    size_bars(3 * m);
    scale_lagged_ok = false;
    launch_repair();
    bars_in_one_block(totals.data() + 2, counters.data());
  }
  // The retriangulation's outcome: where the repair did not settle on the device, its rest, a
  // rebuild where needed, and the bars.
  TopologyStats end_one_block_repair() {
    const gpu::TopologyCounters c = *h_counters.get();
    const bool built = gpu::settled_on_device(c);
    one_read_retriangulations += built;
    TopologyStats stats;
    int64_t flips = finish_repair(c, stats.dropped);
    if (built) keep.resize(static_cast<int64_t>(tris.size()));  // the same memory
    if (flips < 0) flips = mend_folds(stats.folds_refilled);
    if (flips < 0) {
      stats.full = true;
      stats.repair_failed = true;
    } else {
      stats.flips = flips;
    }
    return end_retriangulation(stats, built);
  }
  // A retriangulation's end: the rebuild where it is `full`, and the bars unless built.
  TopologyStats end_retriangulation(TopologyStats stats, bool bars_built) {
    if (stats.full) full_triangulation();
    if (completion_failed) stats.repair_failed = true;
    completion_failed = false;
    have_triangulation = true;
    const TopologyStats sizes = bars_built ? bars_sizes() : filter_and_bars();
    stats.triangles = sizes.triangles;
    stats.bars = sizes.bars;
    return stats;
  }

  // Lawson repair on the device. Returns the flips, or -1 when a rebuild is needed; counts the
  // dropped slivers in `dropped`.
  int64_t repair(int64_t& dropped) {
    launch_repair();
    return finish_repair(read_counters(), dropped);
  }
  // Turned-over triangles: fatal ones call for a rebuild, expendable ones are dropped. The rounds
  // follow at once (flip_round.h), so that a repair reads the device once: they flip nothing where
  // the check found a fatal one, and leave the dropped ones as walls, removed once the rounds
  // settle. The same flips as removing them first: their neighbours' edges are boundary either
  // way, and the rounds' order follows the triangles' order, which the removal keeps. A small
  // triangulation's repair is one launch, which also removes the dropped triangles where the
  // rounds settle and leaves the triangles' count in totals[2] (flip_round.h's OneBlockRepair).
  void launch_repair() {
    const auto m = static_cast<int64_t>(tris.size());
    flags.resize(m);
    if (small_topology()) {
      position.resize(m);
      tris_tmp.resize(m);
      nbrs_tmp.resize(m);
      totals.resize(3);
      gpu::launch_repair_and_keep_in_one_block(
          flip_views(flags.span()), flip_batch.data(),
          {.check = {keep.span(), on_boundary.span(), flags.span()},
           .position = position.span(),
           .tris_out = tris_tmp.span(),
           .nbrs_out = nbrs_tmp.span(),
           .live = totals.data() + 2},
          stream);
    } else {
      begin_flips(flags.span());
      gpu::launch_check_orientation(p.span(), tris.span(), keep.span(), on_boundary.span(),
                                    flags.span(), counters.data(), stream);
      run_flip_rounds(true);
    }
  }
  // The repair's rest once its launch is read: more rounds where they did not settle, the dropped
  // triangles removed.
  int64_t finish_repair(const gpu::TopologyCounters c, int64_t& dropped) {
    if (c.fatal > 0) return -1;
    dropped = c.dropped;
    const int64_t alive = static_cast<int64_t>(tris.size()) - c.dropped;
    if (small_topology() && gpu::settled_on_device(c)) {
      // Removed in the repair's launch, which reset their flipped_round too.
      for (DeviceBuffer<Tri>* t : {&tris, &nbrs}) t->resize(alive);  // the same memory
      if (c.dropped > 0) flipped_round.resize(alive);
      return c.flips;
    }
    const int64_t flips = settle_flips(c);
    if (flips < 0 || c.dropped == 0) return flips;
    // The check counted every triangle it flagged: no wait for the count.
    gpu::keep_triangles(flags.span(), tris, nbrs, {position, tris_tmp, nbrs_tmp}, temp, stream,
                        alive);
    flipped_round.resize(alive);
    MESHD_CUDA_CHECK(cudaMemsetAsync(flipped_round.data(), 0xff, alive * sizeof(int32_t), stream));
    return flips;
  }

  // Lawson flips on the device until every edge passes the in-circle test. Returns the flips,
  // or -1 when a rebuild is needed.
  int64_t flip_to_delaunay() {
    begin_flips();
    run_flip_rounds(true);
    return settle_flips(read_counters());
  }

  // Sizes and resets what the rounds use; the counters start from zero. walls: see FlipBatch.
  void begin_flips(gpu::DeviceSpan<const uint8_t> walls = {}) {
    gpu::launch_begin_flips(flip_views(walls), flip_batch.data(), stream);
  }
  // Sizes what the rounds use; their views, for the device's batch.
  gpu::FlipBatch flip_views(gpu::DeviceSpan<const uint8_t> walls) {
    const int64_t mt = static_cast<int64_t>(tris.size());
    vote.resize(mt);
    partner.resize(mt);
    undecided.resize(kMaxUndecided);
    gpu::size_flip_lists(flip_lists, mt);
    counters.resize(1);
    // The repair's views for the flip rounds (flip_round.h); its first round tests every edge.
    gpu::FlipBatch b{};
    b.p = p.span();
    b.tris = tris.span();
    b.nbrs = nbrs.span();
    b.vote = vote.span();
    b.flipped_round = flipped_round.span();
    b.partner = partner.span();
    b.undecided = undecided.span();
    b.walls = walls;
    b.counters = counters.data();
    for (int k = 0; k < 2; ++k) {
      b.work[k] = flip_lists.work[k].data();
      b.work_stamp[k] = flip_lists.work_stamp[k].data();
    }
    b.voted = flip_lists.voted.data();
    b.voted_stamp = flip_lists.voted_stamp.data();
    b.rounds_per_launch = flip_rounds_per_launch;
    b.tail_items = flip_tail_items;
    b.full = 1;
    return b;
  }

  // From the counters `rc` read after the repair's first launch: launches again, and lets the
  // host decide what the filter could not, until the rounds settle. Returns the flips, or -1
  // when a rebuild is needed.
  int64_t settle_flips(gpu::TopologyCounters rc) {
    for (int launches = 1;; ++launches) {
      if (rc.undecided > kMaxUndecided) return -1;
      if (rc.undecided == 0 && rc.candidates == 0) return rc.flips;
      if (rc.undecided > 0) {
        // The rounds' lists are stale after their last flips: one round again, testing every
        // edge, with the host deciding what the filter could not.
        gpu::launch_full_flip_candidates(flip_batch.data(), step_wave, stream);
        const gpu::TopologyCounters again = read_counters();
        if (again.undecided > kMaxUndecided) return -1;
        const int32_t to_flip = again.undecided > 0 ? decide_on_host(again.undecided) : 0;
        // Exactly co-circular quadruples stay undecided for the filter: once the host says
        // that none of them flips and nothing else does, the triangulation is Delaunay.
        if (again.candidates == 0 && to_flip == 0) return again.flips;
        gpu::launch_flips(flip_batch.data(), step_wave, stream);
        unsettle();  // the host's flips may make new candidates, however few the round found
      }
      if (launches == kMaxFlipLaunches) return -1;
      // Rounds back to back, read once: repairs cascade through a dozen rounds of a few flips
      // each, and a host round trip per round would cost more than the flips.
      run_flip_rounds(false);
      rc = read_counters();
    }
  }

  // Rounds until one finds no candidate (the device's loop), or kRoundsPerBatch rounds launched
  // one by one, of which those after such a round return at once. A repair's first round tests
  // every edge: it gets a full grid of its own, the loop's few blocks the cascade that follows.
  // A small triangulation's rounds, the first included, run in one block (flip_round.h).
  void run_flip_rounds(bool first) {
    if (small_topology()) {
      gpu::launch_flip_rounds_in_one_block(flip_batch.data(), stream);
      return;
    }
    const int rounds_by_kernels = flip_loop_blocks == 0 ? kRoundsPerBatch : first ? 1 : 0;
    for (int r = 0; r < rounds_by_kernels; ++r) {
      gpu::launch_flip_candidates(flip_batch.data(), step_wave, stream);
      gpu::launch_flips(flip_batch.data(), step_wave, stream);
    }
    if (flip_loop_blocks > 0) gpu::launch_flip_loop(flip_batch.data(), flip_loop_blocks, stream);
  }
  // Whether the triangulation's repairs run in one block (kOneBlockRows).
  bool small_topology() const {
    return one_block_topology && static_cast<int64_t>(tris.size()) <= gpu::kOneBlockRows;
  }
  void unsettle() {
    MESHD_CUDA_CHECK(cudaMemsetAsync(&counters.data()->checked, 0, 2 * sizeof(int32_t), stream));
  }

  // The exact fallback: in-circle tests the filter left undecided, on the host with CGAL's exact
  // predicates. Votes for the edges that must flip; returns how many.
  int32_t decide_on_host(int32_t undecided_count) {
    // Only the tests' points cross: reading every point and triangle for each batch of
    // undecided tests cost the gear at 4M nodes 12.7 of its 14.5 seconds (co-circular nodes
    // along its teeth's straight sides leave hundreds of batches).
    std::vector<int32_t> ids(undecided_count);
    std::vector<gpu::InCircleTest> tests(undecided_count);
    in_circle_tests.resize(undecided_count);
    gpu::launch_gather_in_circle_tests(p.span(), tris.span(), nbrs.span(),
                                       {undecided.data(), undecided_count}, in_circle_tests.span(),
                                       stream);
    MESHD_CUDA_CHECK(cudaMemcpyAsync(ids.data(), undecided.data(),
                                     undecided_count * sizeof(int32_t), cudaMemcpyDeviceToHost,
                                     stream));
    in_circle_tests.download(tests.data(), stream);
    sync();
    std::vector<int32_t> flip_ids;
    for (int32_t i = 0; i < undecided_count; ++i) {
      const gpu::InCircleTest& q = tests[i];
      if (in_circle_sign(q.a, q.b, q.c, q.d) > 0) flip_ids.push_back(ids[i]);
    }
    decided.upload(flip_ids.data(), flip_ids.size(), stream);
    gpu::launch_vote_edges(flip_batch.data(), decided.span(), stream);
    sync();  // flip_ids is a host vector
    return static_cast<int32_t>(flip_ids.size());
  }

  // The kept triangles, their bars and the bars' CSR. A small triangulation takes them in one
  // launch (bars_in_one_block.cu). One of up to replayed_triangles runs them as one graph
  // (bars_graph) over room for a few more triangles (padded_rows), with room for three bars a
  // triangle, so that nothing waits for their count and the graph serves the repairs that follow,
  // each dropping a few triangles. A larger one waits for the count, so that its sort covers the
  // bars alone, since its launches cost little beside their work.
  TopologyStats filter_and_bars() {
    const int64_t m = static_cast<int64_t>(tris.size());
    const bool one_block = one_block_topology && gpu::bars_fit_one_block(m, n);
    const bool replayed = !one_block && m <= replayed_triangles;
    const int64_t rows = replayed ? padded_rows(m) : m;
    tris.reserve(rows, stream);
    nbrs.reserve(rows, stream);
    size_filter(rows);
    scale_lagged_ok = false;
    if (one_block) {
      size_bars(3 * m);
      bars_in_one_block();
    } else {
      size_kernels_scratch(rows);
      *h_live.get() = m;
      if (replayed) {
        size_bars(3 * rows);
        bars_graph.run([&] { return bars_key(rows); },
                       [&](cudaStream_t) {
                         filter(rows);
                         bars_and_csr(rows);
                       },
                       stream);
      } else {
        filter(rows);
        read_totals(1);
        sync();
        size_bars((*h_totals.get())[0]);
        bars_and_csr(rows);
      }
    }
    // The device idle at the end: with the CSR's sort still running as the steps begin, memcheck
    // reports garbage reads inside the step graph, unexplained (bench/RESULTS.md, 2026-11-28).
    sync();
    keep.resize(m);  // the same memory
    return bars_sizes();
  }
  // What filter and bars_and_csr do, in one launch: the filter's grid, whose last block builds
  // the bars (bars_in_one_block.cu); over the first *live triangles where live is given (on the
  // device).
  // The totals, and a repair's counters where given, reach h_totals and h_counters at the
  // stream's next wait.
  void bars_in_one_block(const int64_t* live = nullptr,
                         const gpu::TopologyCounters* repair_counters = nullptr) {
    gpu::launch_filter_and_bars(
        {.p = p.span(),
         .tris = tris.span(),
         .nbrs = nbrs.span(),
         .filter = {clearance.span(), clear, fd, nested_index, problem->params.geps * problem->h0},
         .keep = keep.span(),
         .ticket = last_block_ticket.data(),
         .bars = bars.span(),
         .csr_offset = csr_offset.span(),
         .csr_entry = csr_entry.span(),
         .csr_other = csr_other.span(),
         .p_old = p_old.span(),
         .totals = totals.data(),
         .live = live,
         .host_totals = h_totals.get()->data(),
         .counters = repair_counters,
         .host_counters = repair_counters ? h_counters.get() : nullptr},
        stream);
  }
  // m rounded up by at most a sixteenth (a multiple of 256 at least).
  static int64_t padded_rows(int64_t m) {
    int64_t step = 256;
    while (step * 32 <= m) step *= 2;
    return (m + step - 1) / step * step;
  }
  // The counts that bars_and_csr sent, once the stream was waited for; the bars' room trimmed to
  // their count (the same memory).
  TopologyStats bars_sizes() {
    TopologyStats stats;
    stats.bars = (*h_totals.get())[0];
    stats.triangles = (*h_totals.get())[1];
    size_bars(stats.bars);
    return stats;
  }
  void size_filter(int64_t rows) {
    keep.resize(rows);
    totals.resize(3);
    csr_offset.resize(n + 1);
  }
  // What the kernels one by one use besides (filter, bars_and_csr).
  void size_kernels_scratch(int64_t rows) {
    count.resize(rows);
    position.resize(rows);
    degree.resize(n + 1);
  }
  void size_bars(int64_t room) {
    bars.resize(room);
    for (DeviceBuffer<int32_t>* end : {&csr_entry, &csr_other}) end->resize(2 * room);
  }
  // The triangulation's `rows` (reserved; those past tris.size() are room, told apart on the
  // device by totals[2], the live count copied from h_live).
  gpu::DeviceSpan<const Tri> rows_of(const DeviceBuffer<Tri>& t, int64_t rows) const {
    return {t.data(), rows};
  }
  // keep, and the bars' count in totals[0].
  void filter(int64_t rows) {
    int64_t* live = totals.data() + 2;
    MESHD_CUDA_CHECK(
        cudaMemcpyAsync(live, h_live.get(), sizeof(int64_t), cudaMemcpyHostToDevice, stream));
    gpu::launch_centroid_filter(p.span(), clearance.span(), clear, rows_of(tris, rows), fd,
                                nested_index, problem->params.geps * problem->h0, keep.span(), live,
                                stream);
    gpu::launch_count_bars(rows_of(nbrs, rows), keep.span(), count.span(), live, stream);
    gpu::exclusive_scan(count.data(), position.data(), rows, temp, stream);
    gpu::launch_scan_total(position.data(), count.data(), rows, totals.data(), stream);
  }
  // The bars into their room (size_bars), the CSR of their ends by node, and the kept triangles'
  // count in totals[1]; both totals reach h_totals at the next wait.
  void bars_and_csr(int64_t rows) {
    gpu::launch_write_bars(rows_of(tris, rows), rows_of(nbrs, rows), keep.span(), position.span(),
                           bars.span(), totals.data() + 2, stream);
    // Rows filled by counting, not by sorting the ends: a sort cost a 20k-node job's repair 34
    // of its ~180 us (bench/RESULTS.md, 2026-11-28).
    MESHD_CUDA_CHECK(cudaMemsetAsync(degree.data(), 0, (n + 1) * sizeof(int32_t), stream));
    gpu::launch_count_bar_ends(bars.span(), totals.data(), degree.span(), stream);
    gpu::exclusive_scan(degree.data(), csr_offset.data(), n + 1, temp, stream);
    gpu::launch_fill_csr(bars.span(), totals.data(), csr_offset.span(), degree.span(),
                         csr_entry.span(), csr_other.span(), stream);
    MESHD_CUDA_CHECK(cudaMemcpyAsync(p_old.data(), p.data(), n * sizeof(Vec2),
                                     cudaMemcpyDeviceToDevice, stream));
    // Kept triangles, for the stats: position is free again once the bars are written.
    gpu::exclusive_scan(keep.data(), position.data(), rows, temp, stream);
    gpu::launch_scan_total(position.data(), keep.data(), rows, totals.data() + 1, stream);
    read_totals(2);
  }
  // The first `slots` totals into h_totals, once the stream is next waited for.
  void read_totals(int slots) {
    MESHD_CUDA_CHECK(cudaMemcpyAsync(h_totals.get()->data(), totals.data(), slots * sizeof(int64_t),
                                     cudaMemcpyDeviceToHost, stream));
  }
  // What bars_graph's launches depend on: the buffers' places, the sizes (the bars' room follows
  // from rows), and the epoch for the arguments passed by value (the programs, the clearance
  // rule, geps).
  gpu::ReplayGraph::Key bars_key(int64_t rows) const {
    const auto at = [](const void* ptr) { return reinterpret_cast<uint64_t>(ptr); };
    return {epoch,
            static_cast<uint64_t>(n),
            static_cast<uint64_t>(rows),
            at(p.data()),
            at(p_old.data()),
            at(clearance.data()),
            at(tris.data()),
            at(nbrs.data()),
            at(keep.data()),
            at(count.data()),
            at(position.data()),
            at(totals.data()),
            at(bars.data()),
            at(csr_entry.data()),
            at(csr_other.data()),
            at(degree.data()),
            at(csr_offset.data()),
            at(temp.data())};
  }
};

// ---- Engine interface ---------------------------------------------------------------------------

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
  const char* graph = std::getenv("MESHD_GPU_STEP_GRAPH");
  set_step_graph(graph == nullptr || std::string(graph) != "0");
  // For comparison: a small job's steps wait for its retriangulation's outcome, as they did.
  const char* behind = std::getenv("MESHD_GPU_STEPS_BEHIND_REPAIRS");
  set_steps_behind_repairs(behind == nullptr || std::string(behind) != "0");
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
