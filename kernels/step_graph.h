// The step of the DistMesh loop as one CUDA graph: a device-side while loop over move_nodes and
// finish_step (launch.h), which runs up to a StepBatch's limit of steps and stops early where
// the loop must look (a retriangulation, convergence) without a host round trip per step. Small
// meshes are launch-bound: at 20k nodes a step's kernels take a few microseconds, the launches
// and the host's wait for each step's result as long again.
// Built once per engine: its kernels read all their arguments from the StepBatch, so the same
// graph serves every step of every job. Host code; CUDA 12.4 or later (conditional nodes).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "kernels/launch.h"

namespace meshd::gpu {

class StepGraph {
 public:
  // batch: device memory, kept for the graph's life; blocks: move_nodes_wave.
  StepGraph(StepBatch* batch, int64_t blocks, cudaStream_t stream);
  ~StepGraph();
  StepGraph(const StepGraph&) = delete;
  StepGraph& operator=(const StepGraph&) = delete;

  // Runs the batch's steps on `stream` (the batch must be written first, on the same stream).
  void launch(cudaStream_t stream) const;

 private:
  cudaGraph_t graph_ = nullptr;
  cudaGraphExec_t exec_ = nullptr;
};

}  // namespace meshd::gpu
