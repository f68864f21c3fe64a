#include "kernels/loop_graph.h"

#include "kernels/cuda_check.h"

namespace meshd::gpu {

LoopGraph::LoopGraph(const Body& body, cudaStream_t stream) {
  MESHD_CUDA_CHECK(cudaGraphCreate(&graph_, 0));
  try {
    // The loop's condition starts at 1 on every launch: a launch runs at least one pass.
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
    cudaGraph_t pass = loop.conditional.phGraph_out[0];
    MESHD_CUDA_CHECK(cudaStreamBeginCaptureToGraph(stream, pass, nullptr, nullptr, 0,
                                                   cudaStreamCaptureModeThreadLocal));
    try {
      CaptureScope capturing;
      body(more, stream);
    } catch (...) {
      cudaStreamEndCapture(stream, &pass);
      throw;
    }
    MESHD_CUDA_CHECK(cudaStreamEndCapture(stream, &pass));
    MESHD_CUDA_CHECK(cudaGraphInstantiate(&exec_, graph_, 0));
  } catch (...) {
    cudaGraphDestroy(graph_);
    throw;
  }
}

LoopGraph::~LoopGraph() {
  if (exec_ != nullptr) cudaGraphExecDestroy(exec_);
  cudaGraphDestroy(graph_);
}

void LoopGraph::launch(cudaStream_t stream) const {
  MESHD_CUDA_CHECK(cudaGraphLaunch(exec_, stream));
}

}  // namespace meshd::gpu
