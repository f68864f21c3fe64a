#include "kernels/gpu_engine3.h"

#include <cuda_runtime.h>

#include <utility>

#include "core/common/error.h"
#include "kernels/device_buffer.h"
#include "kernels/device_program3.h"
#include "kernels/flip_repair3.h"
#include "kernels/launch.h"
#include "kernels/launch3d.h"
#include "kernels/pinned_value.h"

namespace meshd {

using gpu::Bar3;
using gpu::DeviceBuffer;

struct GpuEngine3::Impl {
  int device = 0;
  cudaStream_t stream = nullptr;
  // The job.
  const Domain3* domain = nullptr;
  const Params3* params = nullptr;
  double h0 = 0.0;
  gpu::DeviceProgram3 geometry;
  gpu::DeviceSizeField3 size;
  // The nodes between two triangulations.
  Nodes3* nodes = nullptr;
  bool stepped = false;  // the device's nodes are ahead of *nodes
  DeviceBuffer<Vec3> p, p_next, momentum, at_triangulation;
  DeviceBuffer<Bar3> bars;
  DeviceBuffer<int64_t> bar_offsets, bar_ends;
  DeviceBuffer<double> length, bar_size, scale;
  DeviceBuffer<gpu::BarSums3> bar_partial;
  DeviceBuffer<gpu::StepSums3> step_partial;
  DeviceBuffer<StepResult> result;
  DeviceBuffer<uint8_t> crowded;
  gpu::PinnedValue<StepResult> h_result;
  // The last triangulation, for the next repair.
  gpu::KeptTetrahedra3 kept;

  void use_device() const { MESHD_CUDA_CHECK(cudaSetDevice(device)); }
};

GpuEngine3::GpuEngine3(int device)
    : impl_((gpu::checked_device(device), std::make_unique<Impl>())) {
  impl_->device = device;
  MESHD_CUDA_CHECK(cudaStreamCreateWithFlags(&impl_->stream, cudaStreamNonBlocking));
  impl_->scale.resize(1);
  impl_->result.resize(1);
}

GpuEngine3::~GpuEngine3() {
  if (impl_->stream != nullptr) {
    cudaSetDevice(impl_->device);
    // The buffers are freed after this: whatever the stream still holds must finish first.
    cudaStreamSynchronize(impl_->stream);
    cudaStreamDestroy(impl_->stream);
  }
}

void GpuEngine3::begin(const Domain3& domain, double h0, const Params3& params) {
  Impl& s = *impl_;
  if (domain.program == nullptr)
    throw Error(ErrorCode::kInvalidArgument, "volume.geometry",
                "the GPU engine evaluates only a compiled geometry (this domain has none)");
  if (domain.size && domain.size_field == nullptr)
    throw Error(ErrorCode::kInvalidArgument, "volume.size",
                "the GPU engine evaluates only a compiled size field (this domain has none)");
  s.use_device();
  s.domain = &domain;
  s.params = &params;
  s.h0 = h0;
  s.nodes = nullptr;
  s.stepped = false;
  s.kept.forget();
  s.geometry.upload(*domain.program, s.stream);
  s.size.upload(domain.size ? domain.size_field : nullptr, s.stream);
}

void GpuEngine3::start(Nodes3& nodes, const Topology3& topology) {
  Impl& s = *impl_;
  s.use_device();
  s.nodes = &nodes;
  s.stepped = false;
  const size_t n = nodes.points.size();
  s.p.upload(nodes.points.data(), n, s.stream);
  s.p_next.resize(n);
  s.momentum.upload(nodes.momentum.data(), n, s.stream);
  s.at_triangulation.upload(nodes.at_triangulation.data(), n, s.stream);
  static_assert(sizeof(Bar3) == sizeof(topology.bars[0]));
  s.bars.upload(reinterpret_cast<const Bar3*>(topology.bars.data()), topology.bars.size(),
                s.stream);
  s.bar_offsets.upload(topology.bar_offsets.data(), topology.bar_offsets.size(), s.stream);
  s.bar_ends.upload(topology.bar_ends.data(), topology.bar_ends.size(), s.stream);
  s.length.resize(topology.bars.size());
  s.bar_size.resize(topology.bars.size());
  s.bar_partial.resize(gpu::nonempty_reduce_blocks_for(static_cast<int64_t>(topology.bars.size())));
  s.step_partial.resize(gpu::nonempty_reduce_blocks_for(static_cast<int64_t>(n)));
  // The uploads read the caller's vectors, which may change once this returns.
  MESHD_CUDA_CHECK(cudaStreamSynchronize(s.stream));
}

StepResult GpuEngine3::step() {
  Impl& s = *impl_;
  s.use_device();
  const Params3& prm = *s.params;
  gpu::launch_measure_bars3(s.p.span(), s.bars.span(), s.size.view(), s.size.graded(),
                            s.length.span(), s.bar_size.span(), s.bar_partial.span(), s.stream);
  gpu::launch_finish_scale3(s.bar_partial.span(), prm.fscale, s.scale.data(), s.stream);
  gpu::MoveArgs3 a;
  a.p = s.p.span();
  a.p_next = s.p_next.span();
  a.momentum = s.momentum.span();
  a.at_triangulation = s.at_triangulation.span();
  a.bars = s.bars.span();
  a.bar_offsets = s.bar_offsets.span();
  a.bar_ends = s.bar_ends.span();
  a.length = s.length.span();
  a.size = s.bar_size.span();
  a.scale = s.scale.data();
  a.fd = s.geometry.view();
  a.band = s.domain->exact_band;
  a.fixed = s.nodes->fixed;
  a.deltat = prm.deltat;
  a.momentum_factor = prm.momentum;
  a.inside = -prm.geps * s.h0;
  a.deps = prm.deps * s.h0;
  a.h0 = s.h0;
  a.partial = s.step_partial.span();
  gpu::launch_move_nodes3(a, s.stream);
  gpu::launch_finish_step3(s.step_partial.span(), s.result.data(), s.stream);
  MESHD_CUDA_CHECK(cudaMemcpyAsync(s.h_result.get(), s.result.data(), sizeof(StepResult),
                                   cudaMemcpyDeviceToHost, s.stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(s.stream));
  std::swap(s.p, s.p_next);
  s.stepped = true;
  return *s.h_result.get();
}

std::vector<int32_t> GpuEngine3::crowded_nodes() {
  Impl& s = *impl_;
  s.use_device();
  const size_t n = s.nodes->points.size();
  s.crowded.resize(n);
  if (n > 0) MESHD_CUDA_CHECK(cudaMemsetAsync(s.crowded.data(), 0, n, s.stream));
  gpu::launch_mark_crowded3(s.bars.span(), s.length.span(), s.bar_size.span(), s.scale.data(),
                            s.nodes->fixed, s.crowded.span(), s.stream);
  std::vector<uint8_t> flags(n);
  s.crowded.download(flags.data(), s.stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(s.stream));
  std::vector<int32_t> out;
  for (size_t i = 0; i < n; ++i)
    if (flags[i]) out.push_back(static_cast<int32_t>(i));
  return out;
}

void GpuEngine3::sync() {
  Impl& s = *impl_;
  if (s.nodes == nullptr || !s.stepped) return;
  s.use_device();
  s.p.download(s.nodes->points.data(), s.stream);
  s.momentum.download(s.nodes->momentum.data(), s.stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(s.stream));
  s.stepped = false;
}

void GpuEngine3::keep_triangulation(const std::vector<std::array<int32_t, 4>>& all, int64_t nodes) {
  Impl& s = *impl_;
  s.use_device();
  s.kept.keep(all, nodes, s.stream);
}

void GpuEngine3::forget_triangulation() { impl_->kept.forget(); }

std::optional<std::vector<std::array<int32_t, 4>>> GpuEngine3::repair_triangulation() {
  Impl& s = *impl_;
  // The nodes the triangulation was kept for live in p from the next start on.
  if (!s.kept.kept() || s.nodes == nullptr) return std::nullopt;
  s.use_device();
  if (!s.kept.repair(s.p.span(), kRepairRounds3, s.stream).usable()) return std::nullopt;
  return s.kept.download(s.stream);
}

}  // namespace meshd
