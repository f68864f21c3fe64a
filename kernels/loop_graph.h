// A CUDA graph that holds one device-side while loop, so that a run of launches loops on the
// device without a host round trip per pass: the step (up to a StepBatch's limit of steps,
// stopping where the loop must look: a retriangulation, convergence). Small meshes are
// launch-bound: at 20k nodes a step's kernels take a few microseconds, the launches and the host's
// wait for each step's result as long again. The body is captured once from the launch wrappers, so
// that they stay the one place that launches their kernels; they read their arguments from device
// memory, so that the same graph serves every pass of every job. Host code; CUDA 12.4 or later
// (conditional nodes).
#pragma once

#include <cuda_runtime.h>

#include <functional>

namespace meshd::gpu {

class LoopGraph {
 public:
  // Launches one pass on `stream`; its last kernel sets the loop's condition through `more`.
  using Body = std::function<void(const cudaGraphConditionalHandle& more, cudaStream_t stream)>;

  LoopGraph(const Body& body, cudaStream_t stream);
  ~LoopGraph();
  LoopGraph(const LoopGraph&) = delete;
  LoopGraph& operator=(const LoopGraph&) = delete;

  // Runs passes on `stream` until one clears the condition; at least one.
  void launch(cudaStream_t stream) const;

 private:
  cudaGraph_t graph_ = nullptr;
  cudaGraphExec_t exec_ = nullptr;
};

}  // namespace meshd::gpu
