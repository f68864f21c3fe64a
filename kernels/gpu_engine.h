// The GPU engine: the whole DistMesh loop on one CUDA device, behind the Engine interface.
//
// Points, triangles, bars and forces stay on the device for the whole job; the host sees the
// scalars of each step and the copies it asks for. Triangulations are repaired on the device by
// parallel Lawson flips. The first one is built from the initial lattice (initial_triangulation.h),
// a refined level's from the coarse level's triangles split on the device (refine_level.h). The
// triangles that survive a removal of points, a refined level's and a repair's folded ones cut
// out are completed with CGAL on the gaps' points alone (complete_gaps.h); CGAL triangulates all
// points on the host only when that fails.
// Device buffers grow and are kept between jobs (the arena): a job no larger than the largest
// one before allocates nothing. One engine per device; not thread-safe.
//
// A plain C++ header: g++ code (the server, tests, meshbench) includes it without CUDA.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/delaunay/delaunay.h"
#include "core/distmesh/engine.h"
#include "kernels/gpu_devices.h"

namespace meshd {

class GpuEngine final : public Engine {
 public:
  // Creates the context and stream on `device`. Throws Error(kUnavailable) without a device.
  explicit GpuEngine(int device = 0);
  ~GpuEngine() override;
  GpuEngine(const GpuEngine&) = delete;
  GpuEngine& operator=(const GpuEngine&) = delete;

  // Meshes a small disk so that modules load and the arena holds a first set of buffers.
  void warm_up();

  // The Delaunay triangulation of `points` alone (delaunay.h's contract, duplicates left out)
  // as the engine's full triangulations build it: the device's point insertion, its hull
  // completed and flipped with exact predicates. For the builder's tests and benchmark; ends the
  // current job. `timing`: the device's seconds from points to triangles, both on the device.
  struct DelaunayTiming {
    double seconds = 0.0;
    int insertion_steps = 0;
    int flip_steps = 0;
  };
  Triangulation delaunay(const std::vector<Vec2>& points, DelaunayTiming* timing = nullptr);

  // How each node sums its bar forces: a gather through the bar CSR (the default: no atomics,
  // the same bits every run and on the CPU) or float atomics from each bar (for comparison).
  enum class ForceSum { kGather, kAtomic };
  void set_force_sum(ForceSum mode);

  // One pass over the nodes per step for a uniform size field (the default): the L0 scale of a
  // step is the one measured by the step before (the bar lengths one step old), except right
  // after a triangulation, instead of a pass over the bars first. Off: that pass every step, as
  // the CPU engine does (its last bits differ all the same: its sums run in another order).
  void set_lagged_scale(bool on);

  // The step as a CUDA graph that runs up to 32 steps per host round trip (loop_graph.h), and a
  // repair's flip rounds in one cooperative launch that runs them until they settle
  // (flip_round.h): the default, unless the environment sets MESHD_GPU_STEP_GRAPH=0. Otherwise
  // their kernels are launched one by one, one step or eight rounds per round trip (for
  // comparison, and for tools that cannot follow a graph).
  void set_step_graph(bool on);
  // With the step graph on: a batch's steps in one cooperative launch (launch.h's steps_together;
  // the default where the device launches cooperatively), or through the graph's loop (off). The
  // same bits either way.
  void set_steps_together(bool on);
  // For tests: the flip loop's rounds per launch (gpu::kLoopFlipRounds by default), after
  // which a repair that still finds candidates launches it again.
  void set_flip_rounds_per_launch(int rounds);
  // For tests: the longest work list of a round that the flip loop leaves to one block
  // (gpu::FlipBatch::tail_items; 0: never).
  void set_flip_tail_items(int items);
  // For tests: the largest triangulation whose bars and CSR run as one replayed graph
  // (replay_graph.h; 2^18 triangles by default, 0: none), and how many such runs there were.
  void set_replayed_triangles(int64_t triangles);
  int64_t bars_replays() const;
  // Partial retriangulations whose repair, compaction and bars the host read once (flip_round.h's
  // OneBlockRepair), for the tests.
  int64_t one_read_retriangulations() const;
  // For tests: whether a small triangulation's repairs (orientation check and flip rounds), and
  // its bars and CSR, run in one block's launch each (flip_round.h's and launch.h's one-block
  // forms; on by default) or as the kernels one by one and the flip loop.
  void set_one_block_topology(bool on);
  // For tests: whether a small job's steps are launched behind its retriangulation's repair, before
  // the host reads the repair's outcome (retriangulate_and_move; on by default, off where the
  // environment sets MESHD_GPU_STEPS_BEHIND_REPAIRS=0), and how many batches ran there. The
  // same bits either way.
  void set_steps_behind_repairs(bool on);
  int64_t steps_behind_repair_batches() const;

  // The host's threads for its share of the finish (kept by reference; null, the default: the
  // caller's thread alone).
  void set_host_pool(ThreadPool* pool) { host_pool_ = pool; }
  ThreadPool* host_pool() override { return host_pool_; }

  const char* name() const override { return "gpu"; }
  int64_t initialize(const CompiledProblem& problem) override;
  int64_t load_points(const CompiledProblem& problem, const std::vector<Vec2>& points) override;
  // On the device (refine_level.h); the split triangles start the next full triangulation.
  int64_t refine(const CompiledProblem& finer) override;
  TopologyStats retriangulate(bool full) override;
  int64_t remove_crowded_points(int64_t max_removed) override;
  StepResult move_points() override;
  void move_points_until(const StepRule& rule, int first_iteration, int limit,
                         std::vector<StepResult>& steps) override;
  // For a small triangulation whose steps go in one cooperative launch: the repair, the bars and
  // the steps behind them, and one wait.
  std::optional<TopologyStats> retriangulate_and_move(const StepRule& rule, int first_iteration,
                                                      int limit,
                                                      std::vector<StepResult>& steps) override;
  int preferred_batch() const override;
  void remove_points(const std::vector<int32_t>& indices) override;
  int64_t remove_boundary_slivers(const CompiledProblem& problem, int64_t max_removed) override;
  int64_t node_count() const override;
  void read_points(std::vector<Vec2>& points) override;
  void read_triangles(std::vector<std::array<int32_t, 3>>& triangles) override;
  void read_mesh(MeshCopy& copy) override;
  QualityStats measure_quality(const Mesh& mesh, bool moved) override;

  int device() const;
  // cudaMalloc calls so far in this process (all engines), to check the arena.
  static int64_t device_allocations();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  ThreadPool* host_pool_ = nullptr;
};

}  // namespace meshd
