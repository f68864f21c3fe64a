// The 3D loop's CPU engine: step3d (and density control's crowded_nodes3d) on the host, behind
// the engine interface (engine3.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh3d/engine3.h"
#include "core/distmesh3d/step3d.h"

namespace meshd {

// The steps on the host, on `pool`'s threads (may be null): step3d itself.
class CpuEngine3 final : public Engine3 {
 public:
  explicit CpuEngine3(ThreadPool* pool) : pool_(pool) {}
  const char* name() const override { return "cpu"; }
  void begin(const Domain3& domain, double h0, const Params3& params) override {
    domain_ = &domain;
    h0_ = h0;
    params_ = &params;
  }
  void start(Nodes3& nodes, const Topology3& topology) override {
    nodes_ = &nodes;
    topology_ = &topology;
  }
  StepResult step() override {
    return step3d(*domain_, *params_, h0_, *topology_, *nodes_, bars_, pool_);
  }
  std::vector<int32_t> crowded_nodes() override {
    return crowded_nodes3d(*topology_, bars_, nodes_->fixed);
  }
  void sync() override {}

 private:
  ThreadPool* pool_;
  const Domain3* domain_ = nullptr;
  double h0_ = 0.0;
  const Params3* params_ = nullptr;
  Nodes3* nodes_ = nullptr;
  const Topology3* topology_ = nullptr;
  BarLengths bars_;
};

}  // namespace meshd
