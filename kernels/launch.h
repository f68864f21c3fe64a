// Launch wrappers of the GPU engine's kernels: plain host declarations over DeviceSpan views.
// Each wrapper returns at once on empty input, launches on the given stream with kBlock threads
// per block and checks the launch. Definitions live beside their kernels in the .cu files.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/delaunay/tri.cuh"
#include "core/distmesh/clearance.cuh"
#include "core/distmesh/initial_points.cuh"
#include "core/distmesh/step_rule.cuh"
#include "core/geometry/program.h"
#include "core/geometry/size_program.h"
#include "kernels/device_span.cuh"

namespace meshd::gpu {

constexpr int kBlock = 256;

MESHD_HD inline int64_t blocks_for(int64_t n) { return (n + kBlock - 1) / kBlock; }

// Bits that hold every index below n: the radix sorts' key width.
inline int bits_for(int64_t n) {
  int bits = 1;
  while ((int64_t{1} << bits) < n) ++bits;
  return bits;
}

// The bar measure reduces as it goes over the bars with at most this many blocks: one resident
// wave on an H100/H200 at full occupancy, so that the one-block kernel that sums the blocks'
// partials reads a thousand of them rather than ten thousand (at a million nodes, 22 us a step
// against 4). The grid depends only on the bar count: the same summation order, and so the same
// bits, every run.
constexpr int64_t kMaxReduceBlocks = 1024;
MESHD_HD inline int64_t reduce_blocks_for(int64_t n) {
  return n < kBlock * kMaxReduceBlocks ? blocks_for(n) : kMaxReduceBlocks;
}
// The same, but at least one block: for a reduction that writes its total (zero) over no items.
MESHD_HD inline int64_t nonempty_reduce_blocks_for(int64_t n) {
  return n > 0 ? reduce_blocks_for(n) : 1;
}

struct BarSums {
  double l2;  // sum of L^2
  double h2;  // sum of h^2
};
// The measures of one step; also the per-block partials of their reduction.
struct StepSums {
  double max_move;
  double max_drift;
  double sum_sq;
  double interior;
  double bar_l2;  // sum over nodes of their bars' L^2 before the step: 2 sum L^2 (gather only)
};

using meshd::Tri;  // core/delaunay/tri.cuh
struct Bar {
  int32_t a, b;
};

// ---- points.cu: initial points and compaction ---------------------------------------------------

// Step 1-2 per grid point: size[k] = h(p) when fd(p) < geps, else 0; the minimum positive size
// goes to *h_min_bits (an unsigned view of a positive double, so atomicMin orders it).
void launch_classify_grid(const InitialGrid& grid, ProgramView fd, SizeView fh, double geps,
                          DeviceSpan<double> size, unsigned long long* h_min_bits,
                          cudaStream_t stream);
// flag[k] = 1 for grid points kept by the size rejection and not within 0.5 h0 h of a fixed node.
void launch_flag_grid(const InitialGrid& grid, DeviceSpan<const double> size,
                      const unsigned long long* h_min_bits, uint64_t seed,
                      DeviceSpan<const Vec2> fixed, DeviceSpan<uint8_t> flag, cudaStream_t stream);
// out[offset + position[k]] = grid point k for every flagged k (position: exclusive scan of flag).
void launch_scatter_grid(const InitialGrid& grid, DeviceSpan<const uint8_t> flag,
                         DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out, int64_t offset,
                         cudaStream_t stream);
// out[position[i]] = in[i] where keep[i].
void launch_compact_points(DeviceSpan<const Vec2> in, DeviceSpan<const uint8_t> keep,
                           DeviceSpan<const int32_t> position, DeviceSpan<Vec2> out,
                           cudaStream_t stream);

// ---- forces.cu: steps 4-8 -----------------------------------------------------------------------

// Step 4: length and midpoint size of each bar (stored where the spans are not empty), and
// scale[0] = fscale * sqrt(sum L^2 / sum h^2) and scale[1] = sum h^2, the blocks' partial sums
// added in a fixed order. `partial` holds nonempty_reduce_blocks_for(bars) entries; `ticket` is 0
// before a launch and after it (one per stream: it counts the blocks done).
struct BarsMeasure {
  BarSums* partial;
  unsigned* ticket;
  double fscale;
  double* scale;
};
void launch_measure_bars(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars, SizeView fh,
                         bool uniform, DeviceSpan<double> length, DeviceSpan<double> size,
                         const BarsMeasure& m, cudaStream_t stream);

// The alternative to the CSR gather, for comparison: each bar adds its force to its two ends
// with float atomics (order, and so the last bits, vary from run to run). force: #2N, zeroed.
void launch_scatter_bar_forces(DeviceSpan<const Vec2> p, DeviceSpan<const Bar> bars,
                               DeviceSpan<const double> size, bool uniform, const double* scale,
                               DeviceSpan<double> force, cudaStream_t stream);

struct MoveArgs {
  DeviceSpan<const Vec2> p;         // #N, positions now
  DeviceSpan<Vec2> p_next;          // #N, positions after the step
  DeviceSpan<const Vec2> p_old;     // #N, positions at the last triangulation
  DeviceSpan<Vec2> velocity;        // #N, last step (momentum), updated
  DeviceSpan<uint8_t> on_boundary;  // #N, written: near the boundary after the step
  DeviceSpan<float> clearance;      // #N, updated: how far inside (clearance.cuh)
  ClearanceRule clear;
  DeviceSpan<const int32_t> csr_offset;  // #N + 1
  DeviceSpan<const int32_t> csr_entry;   // bar * 2 + end; read only for a graded size field
  DeviceSpan<const int32_t> csr_other;   // the entry's far end
  DeviceSpan<const double> size;         // #B, h at the midpoints; unused when uniform
  bool uniform;
  bool nested_index;                   // the geometry nests indexed unions (eval_sdf)
  DeviceSpan<const double> scattered;  // #2N summed forces, or empty to gather through the CSR
  const double* scale;
  ProgramView fd;
  int64_t nfix;
  double h0, deltat, momentum, geps, deps, near_boundary;
  // One per block, and as many blocks (at most move_nodes_wave): max move, max drift, sum of
  // move^2, interior count, sum of bar L^2.
  DeviceSpan<StepSums> partial;
};
// Blocks of move_nodes that `device` runs at once. The step loops over the nodes with at most
// that many: one wave with no tail, and a few hundred partials for finish_step to sum instead of
// thousands (with the bar measure's bounded grid, a step at a million nodes went from 100 to 84 us
// on an H200). The count depends only on the node count and the device model: the same bits
// every run on one kind of GPU.
int64_t move_nodes_wave(int device);

// A run of steps on the device, in device memory: the step graph (loop_graph.h) runs move_nodes and
// finish_step in a loop until finish_step says stop, with no host round trip in between. The host
// writes everything before `count` and sets count to 0; finish_step counts the steps, writes their
// results and swaps args.p and args.p_next after each, so that the next step starts from this
// one's positions.
constexpr int kMaxBatchSteps = 32;
struct StepBatch {
  MoveArgs args;  // partial.size: the blocks with nodes to move (at most move_nodes_wave)
  // The lagged L0 scale for the next step is written to next_scale[0] (null: none), from
  // next_scale[1] = sum h^2 over the bars.
  double* next_scale;
  double fscale;
  StepRule rule;
  int32_t first_iteration;  // the loop's number for the first step (step_rule.cuh)
  int32_t limit;            // 1 to kMaxBatchSteps
  int32_t count;
  int32_t more;  // the cooperative steps' decision after each step, for every block
  StepResult results[kMaxBatchSteps];
};
// Steps 5, 7, 8 per node: gather bar forces (no atomics), Euler step with momentum, projection.
// Always `blocks` blocks (move_nodes_wave), so that one captured graph fits every node count;
// those past args.partial.size return at once.
void launch_move_nodes(const StepBatch* batch, int64_t blocks, cudaStream_t stream);
// The alternative to the step graph's loop where the device launches cooperatively: the batch's
// steps in one launch of `blocks` (args.partial.size) blocks, with a grid barrier between a step's
// moves and its end. args.partial must be followed by room for as many more partials. The same
// bits as move_nodes and finish_step one by one. The batch's arguments come with the launch, not
// copied to `batch` first (one call fewer a batch); the batch ends in `batch`, which may be the
// host's pinned memory (no copy back). Where `measure.on`, the launch first measures the bars as
// launch_measure_bars would, with the same bits (length not stored; the sum of h^2 into
// next_scale[1]).
struct StepsMeasure {
  bool on = false;
  bool uniform = true;
  int64_t blocks = 0;  // nonempty_reduce_blocks_for(bars.size) partials
  DeviceSpan<const Bar> bars;
  SizeView fh{};
  DeviceSpan<double> size;  // where not empty, each bar's size (a graded field's)
  BarSums* partial = nullptr;
  // Where given, the bars' count on the device, for a triangulation whose count the host has not
  // read: bars and size are room, and blocks at least nonempty_reduce_blocks_for(room).
  const int64_t* bar_count = nullptr;
};
// steps_together_fit: whether `blocks` blocks of it run at once on `device`.
bool steps_together_fit(int device, int64_t blocks);
struct TopologyCounters;  // topology.cu's, below
// Where `repair` is given, the steps ride behind a repair whose outcome the host has not read,
// with measure.bar_count given: they run only where it settled on the device (settled_on_device)
// and left bars, and otherwise the batch is left as it was, with no step.
void launch_steps_together(const StepBatch& head, StepBatch* batch, const StepsMeasure& measure,
                           int64_t blocks, cudaStream_t stream,
                           const TopologyCounters* repair = nullptr);
// Sums the partials into the step's result and, with next_scale, the lagged L0 scale for the
// next step, fscale * sqrt(sum L^2 / sum h^2), from the lengths that this step measured and the
// sizes measured at the triangulation (next_scale[1]). In the step graph (`more` given), sets the
// graph's loop condition to whether another step follows: fewer than `limit` ran and the rule does
// not stop here.
void launch_finish_step(StepBatch* batch, const cudaGraphConditionalHandle* more,
                        cudaStream_t stream);

// Step 6: keep[v] = 0 for both non-fixed ends of every bar with L0 > 2 L (keep starts at 1).
void launch_mark_crowded(DeviceSpan<const Bar> bars, DeviceSpan<const double> length,
                         DeviceSpan<const double> size, const double* scale, int64_t nfix,
                         DeviceSpan<uint8_t> keep, cudaStream_t stream);

// ---- topology.cu: triangulation repair, filter, bars --------------------------------------------

struct TopologyCounters {
  int32_t fatal;       // inverted kept triangles that are not boundary slivers
  int32_t dropped;     // inverted expendable triangles
  int32_t candidates;  // edges failing the in-circle test this round
  int32_t undecided;   // in-circle tests the filter could not decide this round
  int32_t flips;       // flips done so far
  // Within a batch of flip rounds: a round has counted its candidates (checked), and one found
  // none (settled): nothing flips any more, so the batch's later rounds would find the same and
  // return at once instead.
  int32_t checked;
  int32_t settled;
  int32_t voted;      // triangles a candidate of this round voted for (flip_round.h)
  int32_t queued[2];  // triangles on the rounds' two work lists (flip_round.h)
};
// Whether a repair's rounds settled with no fatal triangle and nothing left to the host.
MESHD_HD inline bool settled_on_device(const TopologyCounters& c) {
  return c.fatal == 0 && c.undecided == 0 && c.candidates == 0;
}

// alive[t] = 0 for inverted or flat expendable triangles (outside, or boundary slivers: see
// lawson_repair.h); counters->fatal counts the others, which call for a rebuild.
void launch_check_orientation(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                              DeviceSpan<const uint8_t> keep, DeviceSpan<const uint8_t> on_boundary,
                              DeviceSpan<uint8_t> alive, TopologyCounters* counters,
                              cudaStream_t stream);
// alive[t] = whether all three nodes of triangle t are kept (node_kept: #N).
void launch_surviving_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const uint8_t> node_kept,
                                DeviceSpan<uint8_t> alive, cudaStream_t stream);
// Every vertex v of `tris` becomes new_index[v].
void launch_renumber_vertices(DeviceSpan<Tri> tris, DeviceSpan<const int32_t> new_index,
                              cudaStream_t stream);
// Keeps the alive triangles: new index = position[t] (exclusive scan of alive).
void launch_compact_triangles(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                              DeviceSpan<const uint8_t> alive, DeviceSpan<const int32_t> position,
                              DeviceSpan<Tri> tris_out, DeviceSpan<Tri> nbrs_out,
                              cudaStream_t stream);

// The points of an in-circle test: whether d lies inside the circle through a, b, c.
struct InCircleTest {
  Vec2 a, b, c, d;
};
// tests[i] = the points of the in-circle test of edge ids[i] (t * 3 + k, as the flip rounds list
// them), for the host's exact predicate.
void launch_gather_in_circle_tests(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                   DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> ids,
                                   DeviceSpan<InCircleTest> tests, cudaStream_t stream);
// The boundary of the triangulation (edges with no neighbour): next[a] = b for each such edge
// a -> b, counted in counters->candidates. Then hull_turns counts in counters->fatal the boundary
// vertices where it turns right (a reflex corner: the triangles do not cover the convex hull).
// With one boundary loop, each boundary vertex has one outgoing boundary edge.
void launch_hull_links(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                       DeviceSpan<int32_t> next, TopologyCounters* counters, cudaStream_t stream);
void launch_hull_turns(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                       DeviceSpan<const Tri> nbrs, DeviceSpan<const int32_t> next,
                       TopologyCounters* counters, cudaStream_t stream);

// The clean-up's rule (boundary_sliver.cuh) over the kept triangles: node_keep[v] = 0 for the
// node v at the largest angle of each sliver whose three nodes lie on the boundary (fd > -geps),
// unless fixed (v < nfix). node_keep starts at 1.
void launch_mark_boundary_slivers(DeviceSpan<const Vec2> p, DeviceSpan<const Tri> tris,
                                  DeviceSpan<const uint8_t> keep, ProgramView fd, double geps,
                                  int64_t nfix, DeviceSpan<uint8_t> node_keep, cudaStream_t stream);
// The centroid filter's inputs besides the points and triangles (centroid_rule.cuh).
struct CentroidFilter {
  DeviceSpan<const float> clearance;  // #N
  ClearanceRule clear;
  ProgramView fd;
  bool nested_index;
  double geps;
};
// keep[t] = fd(centroid) < -geps, decided by the nodes' clearances where they can. The three
// below take `live` (device memory; null: every row): rows from *live on are room past the
// triangulation, with keep and count 0 and no bars, so that a graph sized for the room serves a
// triangulation that lost a few triangles.
void launch_centroid_filter(DeviceSpan<const Vec2> p, DeviceSpan<const float> clearance,
                            const ClearanceRule& clear, DeviceSpan<const Tri> tris, ProgramView fd,
                            bool nested_index, double geps, DeviceSpan<uint8_t> keep,
                            const int64_t* live, cudaStream_t stream);
// count[t] = number of bars triangle t contributes (edges to a higher or no neighbour with
// either side kept); then, with position = exclusive scan of count, writes them.
void launch_count_bars(DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> keep,
                       DeviceSpan<int32_t> count, const int64_t* live, cudaStream_t stream);
void launch_write_bars(DeviceSpan<const Tri> tris, DeviceSpan<const Tri> nbrs,
                       DeviceSpan<const uint8_t> keep, DeviceSpan<const int32_t> position,
                       DeviceSpan<Bar> bars, const int64_t* live, cudaStream_t stream);
// The CSR of the bars by node. Its entries are bar ends, 2b + e for end e of bars[b]; a node's
// row holds its ends in increasing order, and other[k] the far end of entry k. `bars` may run
// past the *bar_count written (room sized before the count is known): the rest are left out.
// First the degrees (degree zeroed before), then, once csr_offset holds their exclusive scan
// (n + 1 entries), the rows; degree is zero again after.
void launch_count_bar_ends(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                           DeviceSpan<int32_t> degree, cudaStream_t stream);
void launch_fill_csr(DeviceSpan<const Bar> bars, const int64_t* bar_count,
                     DeviceSpan<const int32_t> csr_offset, DeviceSpan<int32_t> degree,
                     DeviceSpan<int32_t> csr_entry, DeviceSpan<int32_t> other, cudaStream_t stream);

// ---- bars_in_one_block.cu: a small triangulation's filter and bars in one launch ----------------

// A small triangulation, of up to this many triangles, takes its repair (flip_round.h), its
// compaction (keep_triangles.h) and its bars (below) in one launch of one block each, the repair
// and compaction of a partial retriangulation in one (flip_round.h's OneBlockRepair);
// one_block.cuh: a block of 1,024 threads holds it in eight rows a thread.
constexpr int64_t kOneBlockRows = 8192;
// What the centroid filter, then count and write the bars, count_bar_ends, fill_csr and the kept
// triangles' scan do one by one, with the same bits: for up to kOneBlockRows triangles over fewer
// nodes. The filter runs on a grid (a block a kOneBlockThreads rows); the last of its blocks to
// finish builds the bars.
inline bool bars_fit_one_block(int64_t rows, int64_t n) {
  return rows <= kOneBlockRows && n < kOneBlockRows;
}
struct OneBlockBars {
  DeviceSpan<const Vec2> p;                  // #N
  DeviceSpan<const Tri> tris, nbrs;          // #M
  CentroidFilter filter;                     // the filter's other inputs
  DeviceSpan<uint8_t> keep;                  // #M, the filter's
  unsigned* ticket;                          // the filter's blocks done: 0 before and after
  DeviceSpan<Bar> bars;                      // room for every bar: three a triangle
  DeviceSpan<int32_t> csr_offset;            // #N + 1
  DeviceSpan<int32_t> csr_entry, csr_other;  // two a bar
  DeviceSpan<Vec2> p_old;                    // #N: set to p, the positions at this triangulation
  int64_t* totals;                           // [0] the bars, [1] the kept triangles
  const int64_t* live = nullptr;             // the triangles' count on the device (null: #M)
  // Sent to the host's pinned memory at the end, so that the host reads them after its wait with
  // no copy of its own (null: not sent): totals[0..1], and *counters (a repair's, before this).
  int64_t* host_totals = nullptr;
  const TopologyCounters* counters = nullptr;
  TopologyCounters* host_counters = nullptr;
};
void launch_filter_and_bars(const OneBlockBars& a, cudaStream_t stream);

}  // namespace meshd::gpu
