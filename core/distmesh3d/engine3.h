// The interface between the 3D DistMesh loop (written once, in distmesh3d.cpp) and the machines
// that run its steps: the CPU engine (cpu_engine3.h) and the GPU engine in kernels/. The loop
// keeps the nodes and builds each triangulation on the host; between two triangulations the
// engine owns the nodes, steps them and measures them, and gives them back when asked.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/step_rule.cuh"
#include "core/distmesh3d/domain3d.h"
#include "core/distmesh3d/params3d.h"
#include "core/distmesh3d/step3d.h"
#include "core/distmesh3d/topology3d.h"

namespace meshd {

class Engine3 {
 public:
  virtual ~Engine3() = default;
  virtual const char* name() const = 0;

  // A new job: its domain, its h0 (> 0, the request's length unit) and constants, all kept by
  // reference until the next begin. Throws Error(kInvalidArgument) for a domain the engine
  // cannot evaluate (the GPU's needs domain.program).
  virtual void begin(const Domain3& domain, double h0, const Params3& params) = 0;
  // After a triangulation: `nodes` (their at_triangulation just set) and `topology` are the
  // engine's, kept by reference, until sync.
  virtual void start(Nodes3& nodes, const Topology3& topology) = 0;
  // Steps 4, 5, 7 and 8 (step3d.h) on the nodes.
  virtual StepResult step() = 0;
  // Step 6 on the last step's bars (crowded_nodes3d, step3d.h).
  virtual std::vector<int32_t> crowded_nodes() = 0;
  // Brings the nodes given to start up to date with every step since (nothing, when no step
  // ran since the last sync or start).
  virtual void sync() = 0;
};

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
