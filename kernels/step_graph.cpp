#include "kernels/step_graph.h"

#include "kernels/cuda_check.h"

namespace meshd::gpu {

StepGraph::StepGraph(StepBatch* batch, int64_t blocks, cudaStream_t stream) {
  MESHD_CUDA_CHECK(cudaGraphCreate(&graph_, 0));
  try {
    // The loop's condition starts at 1 on every launch: a batch runs at least one step.
    cudaGraphConditionalHandle more;
    MESHD_CUDA_CHECK(
        cudaGraphConditionalHandleCreate(&more, graph_, 1, cudaGraphCondAssignDefault));
    cudaGraphNodeParams loop{};
    loop.type = cudaGraphNodeTypeConditional;
    loop.conditional.handle = more;
    loop.conditional.type = cudaGraphCondTypeWhile;
    loop.conditional.size = 1;
    cudaGraphNode_t node;
    MESHD_CUDA_CHECK(cudaGraphAddNode(&node, graph_, nullptr, nullptr, 0, &loop));
    cudaGraph_t body = loop.conditional.phGraph_out[0];
    // The body is captured from the launch wrappers, so that they stay the one place that
    // launches these kernels.
    MESHD_CUDA_CHECK(cudaStreamBeginCaptureToGraph(stream, body, nullptr, nullptr, 0,
                                                   cudaStreamCaptureModeThreadLocal));
    try {
      CaptureScope capturing;
      launch_move_nodes(batch, blocks, stream);
      launch_finish_step(batch, &more, stream);
    } catch (...) {
      cudaStreamEndCapture(stream, &body);
      throw;
    }
    MESHD_CUDA_CHECK(cudaStreamEndCapture(stream, &body));
    MESHD_CUDA_CHECK(cudaGraphInstantiate(&exec_, graph_, 0));
  } catch (...) {
    cudaGraphDestroy(graph_);
    throw;
  }
}

StepGraph::~StepGraph() {
  if (exec_ != nullptr) cudaGraphExecDestroy(exec_);
  cudaGraphDestroy(graph_);
}

void StepGraph::launch(cudaStream_t stream) const {
  MESHD_CUDA_CHECK(cudaGraphLaunch(exec_, stream));
}

}  // namespace meshd::gpu
