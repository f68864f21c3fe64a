// The 3D GPU engine: the steps of the 3D DistMesh loop on one CUDA device, behind Engine3.
//
// Between two triangulations the nodes, their momentum and the bars stay on the device: a step
// is four launches and one read of its three measures. The geometry and the size field are the
// request's compiled programs (Domain3::program, ::size_field), copied to the device once per job
// and evaluated by the same code as on the host (sdf3_eval.cuh, size_field3_eval.cuh).
// The engine keeps the last triangulation the host built and repairs it by flips on the device
// for the moved nodes (flip_repair3.h); the host builds where a repair gives up, and builds the
// final triangulation; the finish runs on the host (distmesh3d.h). Device buffers grow and are
// kept between jobs. One engine per device; not thread-safe.
//
// A plain C++ header: g++ code includes it without CUDA.
#pragma once

#include <memory>

#include "core/distmesh3d/engine3.h"

namespace meshd {

class GpuEngine3 final : public Engine3 {
 public:
  // Creates its stream on `device`. Throws Error(kUnavailable) without a device.
  explicit GpuEngine3(int device = 0);
  ~GpuEngine3() override;
  GpuEngine3(const GpuEngine3&) = delete;
  GpuEngine3& operator=(const GpuEngine3&) = delete;

  const char* name() const override { return "gpu"; }
  void begin(const Domain3& domain, double h0, const Params3& params) override;
  void start(Nodes3& nodes, const Topology3& topology) override;
  StepResult step() override;
  std::vector<int32_t> crowded_nodes() override;
  void sync() override;
  void keep_triangulation(const std::vector<std::array<int32_t, 4>>& all, int64_t nodes) override;
  void forget_triangulation() override;
  std::optional<std::vector<std::array<int32_t, 4>>> repair_triangulation() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshd
