// The interface between the DistMesh loop (written once, in distmesh.cpp) and the machines that
// run its steps: the CPU engine here, the GPU engine in kernels/. An engine owns the points,
// triangles and bars of one job at a time; the loop sees only scalars and asks for copies when
// it needs them (snapshots, clean-up, the result).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/vec2.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/step_rule.cuh"
#include "core/mesh/mesh.h"
#include "core/mesh/quality.h"

namespace meshd {

class ThreadPool;

// Nodes within this distance of the boundary (times h0) count as boundary nodes for the
// triangulation repair: a kept triangle of three of them that turns over is a boundary sliver
// collapsing onto a convex curve, which the repair drops instead of rebuilding (lawson_repair.h).
constexpr double kNearBoundaryRelative = 0.6;

// Memory one DistMesh iteration must move at the least, every array it reads or writes
// touched once: per node the position (read, and written to the other buffer), momentum (read
// and written), the position at the last triangulation, the boundary flag and the CSR offset
// (85 bytes); per bar its two ends and its two CSR entries (16 bytes), and for a graded size
// field its midpoint size, written and read (16 more).
inline double iteration_bytes(int64_t nodes, int64_t bars, bool graded) {
  return 85.0 * static_cast<double>(nodes) + (graded ? 32.0 : 16.0) * static_cast<double>(bars);
}

struct TopologyStats {
  int64_t triangles = 0;  // kept inside the domain
  int64_t bars = 0;
  int64_t flips = 0;            // edge flips of a repair
  bool full = true;             // a full triangulation rather than a repair
  bool repair_failed = false;   // a repair was asked for, but the engine rebuilt from scratch
  int64_t dropped = 0;          // turned-over boundary slivers a repair removed
  bool folds_refilled = false;  // a repair cut out turned-over triangles and filled the hole
};

// What the finish (distmesh.cpp) reads from an engine once the relaxation is over.
struct MeshCopy {
  std::vector<Vec2> points;                       // #N, fixed first
  std::vector<std::array<int32_t, 3>> triangles;  // #M, the kept triangles
  std::vector<int32_t> boundary;  // boundary_half_edges(triangles) (core/mesh/boundary.h)
  // Where the engine knows them: the triangles, increasing, that the worst-element optimisation
  // starts from (optimize_worst.h), so that it need not measure all of them.
  std::optional<std::vector<int32_t>> below;
  // Every point is a corner of a triangle and every triangle turns counter-clockwise: assemble_mesh
  // has nothing to renumber or turn.
  bool tidy = false;
  // Where the engine counted them: no free interior node has exactly three triangles, so the
  // finish need not look for trapped nodes (trapped_nodes.h). The GPU engine counts on the device.
  bool none_trapped = false;
};

// max_removed for a removal that may take any number of nodes.
constexpr int64_t kRemoveAny = INT64_MAX;

class Engine {
 public:
  virtual ~Engine() = default;
  virtual const char* name() const = 0;

  // Steps 1-2: loads `problem` (kept by reference until the next call) and places the initial
  // points, fixed points first. Returns the node count.
  virtual int64_t initialize(const CompiledProblem& problem) = 0;
  // Loads `problem` like initialize, but starts from `points` (#N by 2, fixed points first):
  // the next level of a multilevel run. Returns the node count.
  virtual int64_t load_points(const CompiledProblem& problem, const std::vector<Vec2>& points) = 0;
  // The next level of a multilevel run (refine.h): this level's mesh split over its edges'
  // midpoints for `finer` (kept by reference, as by initialize), renumbered along a Hilbert curve
  // (spatial_order.h). By default on the host, through read_points, read_triangles and
  // load_points; the GPU engine refines on the device and keeps the split triangles as the start
  // of its next full triangulation. Returns the node count.
  virtual int64_t refine(const CompiledProblem& finer);
  // Step 3: Delaunay triangulation (from scratch when `full`, otherwise the engine may repair
  // the previous one), the centroid filter and the bar list.
  virtual TopologyStats retriangulate(bool full) = 0;
  // Steps 4 and 6: removes both ends (unless fixed) of every bar with L0 > 2 L, or nothing when
  // more than `max_removed` would go. Returns how many points went; the caller must
  // retriangulate in full when any did.
  virtual int64_t remove_crowded_points(int64_t max_removed) = 0;
  // Steps 4, 5, 7, 8: bar forces, Euler step, projection onto the boundary; also measures
  // step 3's test for the next iteration (the drift since the last triangulation).
  virtual StepResult move_points() = 0;
  // Runs move_points up to `limit` times and appends each step's result to `steps`; stops after
  // the first step at which `rule.stops(result, first_iteration + k, settling)` (k from 0),
  // settling being rule.settling carried on by rule.settle over the steps so far. By default one
  // move_points after the other; the GPU engine runs them on the device with no host round trip
  // in between.
  virtual void move_points_until(const StepRule& rule, int first_iteration, int limit,
                                 std::vector<StepResult>& steps);
  // retriangulate(false) followed by move_points_until(rule, first_iteration, limit, steps), where
  // an engine can start the steps before it learns the repair's outcome (one wait for both):
  // returns the triangulation's stats, the steps appended. Otherwise (the default) does nothing
  // and returns nothing, and the caller calls the two.
  virtual std::optional<TopologyStats> retriangulate_and_move(const StepRule& rule,
                                                              int first_iteration, int limit,
                                                              std::vector<StepResult>& steps);
  // How many steps the loop should ask for at once: 1 where a step is long enough that the host
  // round trip is nothing (the default), more where it is not. The loop reports the steps of a
  // batch, and checks for cancellation, only after the batch.
  virtual int preferred_batch() const { return 1; }
  // Removes the given (non-fixed) nodes; the caller retriangulates in full afterwards.
  virtual void remove_points(const std::vector<int32_t>& indices) = 0;
  // The boundary clean-up's removal (cleanup.h) over the kept triangles. Returns how many nodes
  // went; the caller retriangulates in full when any did. By default on the host, from copies of
  // the points and triangles (cleanup.cpp); the GPU engine finds them where they are.
  // Nothing goes when more than `max_removed` would.
  virtual int64_t remove_boundary_slivers(const CompiledProblem& problem, int64_t max_removed);

  // The finish's copy of the current mesh. By default read_points, read_triangles and
  // boundary_half_edges on the host; the GPU engine finds the boundary from its triangles' links,
  // and the triangles under the optimisation's threshold, on the device.
  virtual void read_mesh(MeshCopy& copy);
  // The quality of `mesh`, which assemble_mesh made from the last read_mesh's copy after the
  // optimisation moved some of its points (`moved`). By default summarize_quality on the host; the
  // GPU engine measures a tidy copy's triangles where they are.
  virtual QualityStats measure_quality(const Mesh& mesh, bool moved);

  // Threads for the host's share of the finish (the worst-element optimisation); null: the
  // caller's thread alone.
  virtual ThreadPool* host_pool() { return nullptr; }

  virtual int64_t node_count() const = 0;
  virtual void read_points(std::vector<Vec2>& points) = 0;
  virtual void read_triangles(std::vector<std::array<int32_t, 3>>& triangles) = 0;
};

}  // namespace meshd
