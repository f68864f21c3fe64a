// The CPU engine: DistMesh's steps over all cores, CGAL for the triangulation.
//
// Invariants between calls: p_ holds the nodes, fixed ones first (indices < nfix_); after a
// retriangulation, dt_ is the Delaunay triangulation of p_ (repaired by edge flips when the
// points only drifted, rebuilt by CGAL otherwise), triangles_ those of its triangles whose
// centroid lies inside, bars_ their unique edges, and bar_csr_ lists for each node the bars that
// end there, so that each node sums its forces alone: no atomics, and the same bits for any number
// of threads.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/delaunay/delaunay.h"
#include "core/distmesh/clearance.cuh"
#include "core/distmesh/engine.h"

namespace meshd {

class CpuEngine final : public Engine {
 public:
  explicit CpuEngine(ThreadPool& pool) : pool_(pool) {}

  const char* name() const override { return "cpu"; }
  int64_t initialize(const CompiledProblem& problem) override;
  int64_t load_points(const CompiledProblem& problem, const std::vector<Vec2>& points) override;
  TopologyStats retriangulate(bool full) override;
  int64_t remove_crowded_points(int64_t max_removed) override;
  StepResult move_points() override;
  void remove_points(const std::vector<int32_t>& indices) override;
  ThreadPool* host_pool() override { return &pool_; }
  int64_t node_count() const override { return static_cast<int64_t>(p_.size()); }
  void read_points(std::vector<Vec2>& points) override { points = p_; }
  void read_triangles(std::vector<std::array<int32_t, 3>>& triangles) override {
    triangles = triangles_;
  }

 private:
  // Step 4: bar lengths L, sizes at the midpoints, and the factor that turns sizes into target
  // lengths (L0 = hbar * scale). Fills bar_length_ and bar_size_.
  double measure_bars();
  void build_bar_csr();
  void keep_points(const std::vector<char>& remove);
  // Resets the per-node state after the node set changed.
  void reset_node_state();

  ThreadPool& pool_;
  const CompiledProblem* problem_ = nullptr;
  std::vector<Vec2> p_;            // #N by 2
  std::vector<Vec2> pold_;         // #N by 2, positions at the last triangulation
  std::vector<Vec2> velocity_;     // #N by 2, the last step (momentum)
  std::vector<char> on_boundary_;  // #N: near the boundary at the last step (fixed: at load)
  std::vector<float> clearance_;   // #N: how far inside each node is known to be (clearance.cuh)
  ClearanceRule clearance_rule_{};
  int64_t nfix_ = 0;
  Triangulation dt_;                               // the full Delaunay triangulation
  std::vector<char> dt_keep_;                      // #M of dt_: centroid inside
  std::vector<std::array<int32_t, 3>> triangles_;  // #M by 3, those kept inside
  std::vector<std::array<int32_t, 2>> bars_;       // #B by 2
  std::vector<double> bar_length_;                 // #B
  std::vector<double> bar_size_;                   // #B, h at the midpoint
  std::vector<Vec2> bar_force_;                    // #B, force on bars_[b][0]
  std::vector<int32_t> csr_offset_;                // #N + 1
  std::vector<int32_t> csr_entry_;                 // #2B: bar * 2 + (0 first end, 1 second)
};

}  // namespace meshd
