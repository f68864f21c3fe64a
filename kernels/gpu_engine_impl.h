// The GPU engine's state (GpuEngine::Impl): the job's buffers on the device and the host's view
// of them, and the operations on them, defined by concept: the problem and the node set
// (gpu_engine_nodes.cpp), the steps (gpu_engine_steps.cpp), triangulations from scratch and
// completions (gpu_engine_triangulation.cpp), repairs by flips (gpu_engine_repairs.cpp), and the
// filter, bars and CSR (gpu_engine_bars.cpp); gpu_engine.cpp puts them behind the Engine
// interface. Internal to kernels/: host code, included by those files alone.
#pragma once

#include <cuda_runtime.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/engine.h"
#include "kernels/complete_gaps.h"
#include "kernels/device_buffer.h"
#include "kernels/finish_mesh.h"
#include "kernels/flip_round.h"
#include "kernels/gpu_engine.h"
#include "kernels/lattice_triangulation.h"
#include "kernels/launch.h"
#include "kernels/loop_graph.h"
#include "kernels/pinned_value.h"
#include "kernels/point_insertion.h"
#include "kernels/refine_level.h"
#include "kernels/replay_graph.h"

namespace meshd {

using gpu::Bar;
using gpu::BarSums;
using gpu::DeviceBuffer;
using gpu::PinnedValue;
using gpu::StepSums;
using gpu::Tri;

// Triangulations up to this size get their bars through one graph (filter_and_bars).
constexpr int64_t kReplayedTriangles = int64_t{1} << 18;

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

  void load_problem(const CompiledProblem& prob);

  // After the node set changed: no momentum, no triangulation, drift "infinite".
  void reset_node_state();

  // Keeps the nodes with flags[i] = 1, in order. Returns how many went; with none, or more than
  // max_removed, leaves the nodes and their triangulation as they are (and returns 0).
  int64_t compact_nodes(int64_t max_removed);

  // Copies the triangles with alive[t] into tris_tmp, in order, and their links into nbrs_tmp
  // (-1 where the neighbour is not alive). Returns how many. `count` holds the scan.
  int64_t compact_alive_triangles(const DeviceBuffer<uint8_t>& alive);

  // Completes tris and nbrs (triangles of some of the current nodes, linked) for the next full
  // triangulation (complete_gaps.h); the nodes may have moved since those triangles were made,
  // so the flips check orientations first. Returns false when the completion failed: then the
  // next full triangulation starts over with CGAL, and reports a fallback.
  bool prepare_completion();
  // The completion once the tries of complete_gaps failed. Triangles outside the domain, flat
  // ones between the hull and a straight side above all, can come to overlap as their nodes move
  // without any of them turning over, and their walls then cross; eroding the triangles next to
  // the gaps need not reach them. The domain's own triangles (the centroid filter's) bound the
  // gaps instead, as on the host's refinement: a last resort, since every node on the domain's
  // boundary then bounds a gap (0.9 s a completion on a coastline of 640k nodes).
  bool complete_from_domain_triangles();

  // Step 4. The step itself needs only the sizes of a graded field; density control needs the
  // lengths and sizes of every bar.
  void measure_bars(bool for_density_control);
  // measure_bars(false) as the cooperative steps' first work: the arguments for their launch.
  gpu::StepsMeasure measure_in_steps();
  // Sizes a measure's buffers; returns its blocks.
  int64_t size_measure(bool for_density_control);

  // Runs up to `limit` steps (4, 5, 7, 8) in one launch of the step graph; one, launched
  // directly, when each step needs the host first (the bar measure of the exact scale, the
  // atomic force sums) or without the graph. A graded field's sizes are measured once per
  // topology, at the first step after a triangulation, as the CPU engine does. Returns how many
  // ran; their results are in h_batch.
  int run_steps(const StepRule& rule, int first_iteration, int limit);
  // Whether steps keep the L0 scale of the step before (set_lagged_scale).
  bool lagged_steps() const;
  // Whether a batch of up to `limit` steps runs in one cooperative launch. A lone step costs less
  // launched directly than through the graph's loop (on an H200 at 1M nodes, a step of the exact
  // scale took 119-130 us through it, 110-122 us directly). A wave of blocks or more (about 100k
  // nodes on an H200) takes the graph's loop: there a step's work hides the loop's launches, and
  // the cooperative kernel, all of a step's code in one, was slower on plate_with_holes at 1M
  // nodes (110 against 104 us a step).
  bool steps_go_together(int limit) const;
  // run_steps' launch; returns whether the steps keep the lagged scale, for end_steps once the
  // host has waited. `behind_repair`: the steps go together (steps_go_together), behind the
  // repair whose counters these are and the bars it leaves, both not read yet
  // (launch_repair_and_bars).
  bool launch_steps(const StepRule& rule, int first_iteration, int limit,
                    const gpu::TopologyCounters* behind_repair = nullptr);
  // After the wait for launch_steps: how many steps ran (none behind a repair that did not settle,
  // which leaves the batch as the host set it); their results are in h_batch.
  int end_steps(bool lagged);
  // Batches of steps until `limit` ran or the rule stops (GpuEngine::move_points_until), the
  // results appended to `steps`; the first batch's `ran` steps are in h_batch already where not 0.
  void steps_until(const StepRule& rule, int first_iteration, int limit,
                   std::vector<StepResult>& steps, int ran);

  // ---- Step 3 ----

  std::vector<Vec2> download_points();

  // A triangulation from scratch: the device's point insertion, its hull completed and flipped
  // with exact predicates; CGAL on the host where that fails (a completion's checks).
  void full_triangulation();

  bool triangulate_on_device();

  // The initial triangulation (lattice_triangulation.h) for the first retriangulate; without
  // it (its completion failed) the first one is built from scratch.
  void prepare(const InitialGrid& grid);

  // Flips the prepared triangulation to Delaunay. Returns the flips, or -1 when it cannot (a
  // triangle turned over): then the caller triangulates with CGAL.
  int64_t flip_prepared();

  // Whether the triangulation covers the convex hull of all n nodes, as a full one does: a
  // disk (2 n - 2 - h triangles for h edges on its boundary) whose boundary never turns right.
  // After a repair that dropped collapsed slivers this is usually still so, and then the
  // repaired triangulation is the one CGAL would build.
  bool covers_hull();

  void reset_counters();
  const gpu::TopologyCounters& read_counters();

  // repair, and where a node crossed an edge (a triangle turned over, which flips cannot undo)
  // the fold cut out and filled (refill_folds.h, here through complete_gaps.h), then flipped.
  // Returns the flips, or -1 when a rebuild is needed; `refilled` tells whether a fold was mended.
  int64_t repair_folds_too(int64_t& dropped, bool& refilled);
  // After a repair that called for a rebuild: the fold cut out and filled, then flipped.
  int64_t mend_folds(bool& refilled);

  // Whether a partial retriangulation's repair removes its dropped triangles in the same launch,
  // with the filter and the bars behind it before the host reads (flip_round.h's OneBlockRepair).
  bool one_block_retriangulation() const;
  // A partial retriangulation's repair and its filter and bars (one_block_retriangulation), as
  // repair_folds_too and filter_and_bars with one read where the repair settles on the device
  // (flip_round.h's OneBlockRepair). The bars' launch sends the repair's counters and its totals
  // to the host's memory; end_one_block_repair reads them after the host's wait.
  void launch_repair_and_bars();
  // The retriangulation's outcome: where the repair did not settle on the device, its rest, a
  // rebuild where needed, and the bars.
  TopologyStats end_one_block_repair();
  // A retriangulation's end: the rebuild where it is `full`, and the bars unless built.
  TopologyStats end_retriangulation(TopologyStats stats, bool bars_built);

  // Lawson repair on the device. Returns the flips, or -1 when a rebuild is needed; counts the
  // dropped slivers in `dropped`.
  int64_t repair(int64_t& dropped);
  // Turned-over triangles: fatal ones call for a rebuild, expendable ones are dropped. The rounds
  // follow at once (flip_round.h), so that a repair reads the device once: they flip nothing where
  // the check found a fatal one, and leave the dropped ones as walls, removed once the rounds
  // settle. The same flips as removing them first: their neighbours' edges are boundary either
  // way, and the rounds' order follows the triangles' order, which the removal keeps. A small
  // triangulation's repair is one launch, which also removes the dropped triangles where the
  // rounds settle and leaves the triangles' count in totals[2] (flip_round.h's OneBlockRepair).
  void launch_repair();
  // The repair's rest once its launch is read: more rounds where they did not settle, the dropped
  // triangles removed.
  int64_t finish_repair(const gpu::TopologyCounters c, int64_t& dropped);

  // Lawson flips on the device until every edge passes the in-circle test. Returns the flips,
  // or -1 when a rebuild is needed.
  int64_t flip_to_delaunay();

  // Sizes and resets what the rounds use; the counters start from zero. walls: see FlipBatch.
  void begin_flips(gpu::DeviceSpan<const uint8_t> walls = {});
  // Sizes what the rounds use; their views, for the device's batch.
  gpu::FlipBatch flip_views(gpu::DeviceSpan<const uint8_t> walls);

  // From the counters `rc` read after the repair's first launch: launches again, and lets the
  // host decide what the filter could not, until the rounds settle. Returns the flips, or -1
  // when a rebuild is needed.
  int64_t settle_flips(gpu::TopologyCounters rc);

  // Rounds until one finds no candidate (the device's loop), or kRoundsPerBatch rounds launched
  // one by one, of which those after such a round return at once. A repair's first round tests
  // every edge: it gets a full grid of its own, the loop's few blocks the cascade that follows.
  // A small triangulation's rounds, the first included, run in one block (flip_round.h).
  void run_flip_rounds(bool first);
  // Whether the triangulation's repairs run in one block (kOneBlockRows).
  bool small_topology() const;
  void unsettle();

  // The exact fallback: in-circle tests the filter left undecided, on the host with CGAL's exact
  // predicates. Votes for the edges that must flip; returns how many.
  int32_t decide_on_host(int32_t undecided_count);

  // The kept triangles, their bars and the bars' CSR. A small triangulation takes them in one
  // launch (bars_in_one_block.cu). One of up to replayed_triangles runs them as one graph
  // (bars_graph) over room for a few more triangles (padded_rows), with room for three bars a
  // triangle, so that nothing waits for their count and the graph serves the repairs that follow,
  // each dropping a few triangles. A larger one waits for the count, so that its sort covers the
  // bars alone, since its launches cost little beside their work.
  TopologyStats filter_and_bars();
  // What filter and bars_and_csr do, in one launch: the filter's grid, whose last block builds
  // the bars (bars_in_one_block.cu); over the first *live triangles where live is given (on the
  // device).
  // The totals, and a repair's counters where given, reach h_totals and h_counters at the
  // stream's next wait.
  void bars_in_one_block(const int64_t* live = nullptr,
                         const gpu::TopologyCounters* repair_counters = nullptr);
  // m rounded up by at most a sixteenth (a multiple of 256 at least).
  static int64_t padded_rows(int64_t m);
  // The counts that bars_and_csr sent, once the stream was waited for; the bars' room trimmed to
  // their count (the same memory).
  TopologyStats bars_sizes();
  void size_filter(int64_t rows);
  // What the kernels one by one use besides (filter, bars_and_csr).
  void size_kernels_scratch(int64_t rows);
  void size_bars(int64_t room);
  // The triangulation's `rows` (reserved; those past tris.size() are room, told apart on the
  // device by totals[2], the live count copied from h_live).
  gpu::DeviceSpan<const Tri> rows_of(const DeviceBuffer<Tri>& t, int64_t rows) const;
  // keep, and the bars' count in totals[0].
  void filter(int64_t rows);
  // The bars into their room (size_bars), the CSR of their ends by node, and the kept triangles'
  // count in totals[1]; both totals reach h_totals at the next wait.
  void bars_and_csr(int64_t rows);
  // The first `slots` totals into h_totals, once the stream is next waited for.
  void read_totals(int slots);
  // What bars_graph's launches depend on: the buffers' places, the sizes (the bars' room follows
  // from rows), and the epoch for the arguments passed by value (the programs, the clearance
  // rule, geps).
  gpu::ReplayGraph::Key bars_key(int64_t rows) const;
};

}  // namespace meshd
