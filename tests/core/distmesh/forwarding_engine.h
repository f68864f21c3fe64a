// An engine that hands every call to a CpuEngine, for tests that watch or change a few of the
// calls the loop makes: subclass it and override those.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"

namespace meshd::testing {

class ForwardingEngine : public Engine {
 public:
  explicit ForwardingEngine(ThreadPool& pool) : cpu_(pool) {}

  const char* name() const override { return "cpu, forwarded"; }
  int64_t initialize(const CompiledProblem& p) override { return cpu_.initialize(p); }
  int64_t load_points(const CompiledProblem& p, const std::vector<Vec2>& pts) override {
    return cpu_.load_points(p, pts);
  }
  TopologyStats retriangulate(bool full) override { return cpu_.retriangulate(full); }
  int64_t remove_crowded_points(int64_t max_removed) override {
    return cpu_.remove_crowded_points(max_removed);
  }
  StepResult move_points() override { return cpu_.move_points(); }
  void remove_points(const std::vector<int32_t>& indices) override { cpu_.remove_points(indices); }
  int64_t remove_boundary_slivers(const CompiledProblem& p, int64_t max_removed) override {
    return cpu_.remove_boundary_slivers(p, max_removed);
  }
  int64_t node_count() const override { return cpu_.node_count(); }
  void read_points(std::vector<Vec2>& points) override { cpu_.read_points(points); }
  void read_triangles(std::vector<std::array<int32_t, 3>>& t) override { cpu_.read_triangles(t); }

 protected:
  CpuEngine cpu_;
};

}  // namespace meshd::testing
