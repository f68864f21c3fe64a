#include "kernels/replay_graph.h"

#include <utility>
#include <vector>

#include "kernels/cuda_check.h"

namespace meshd::gpu {

ReplayGraph::~ReplayGraph() {
  for (Slot& slot : slots_)
    if (slot.exec != nullptr) cudaGraphExecDestroy(slot.exec);
}

void ReplayGraph::run(const std::function<Key()>& key, const Body& body, cudaStream_t stream) {
  const Key now = key();
  for (Slot& slot : slots_) {
    if (slot.exec != nullptr && slot.key == now) {
      MESHD_CUDA_CHECK(cudaGraphLaunch(slot.exec, stream));
      ++replays_;
      return;
    }
  }
  if (now != direct_[0] && now != direct_[1]) {
    body(stream);
    direct_[next_direct_] = key();
    next_direct_ = (next_direct_ + 1) % 2;
    return;
  }
  Slot& slot = slots_[next_slot_];
  next_slot_ = (next_slot_ + 1) % 2;
  capture(slot, now, body, stream);
  MESHD_CUDA_CHECK(cudaGraphLaunch(slot.exec, stream));
  ++replays_;
}

void ReplayGraph::capture(Slot& slot, const Key& key, const Body& body, cudaStream_t stream) {
  slot.key.clear();  // the slot is void until its graph is whole
  cudaGraph_t graph = nullptr;
  MESHD_CUDA_CHECK(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal));
  try {
    CaptureScope capturing;
    body(stream);
  } catch (...) {
    cudaStreamEndCapture(stream, &graph);
    if (graph != nullptr) cudaGraphDestroy(graph);
    throw;
  }
  MESHD_CUDA_CHECK(cudaStreamEndCapture(stream, &graph));
  // An update keeps the executable graph and changes its nodes' arguments: cheaper than a new
  // instantiation, and possible whenever the launches are the same ones. Tried only then, since
  // the sizes choose between launches (a small scan is one kernel, a large one two): a failed
  // update is an error of the API's, which compute-sanitizer reports.
  Shape shape = shape_of(graph);
  cudaGraphExecUpdateResultInfo info{};
  if (slot.exec == nullptr || shape != slot.shape ||
      cudaGraphExecUpdate(slot.exec, graph, &info) != cudaSuccess) {
    cudaGetLastError();  // a failed update is not an error of the job's
    if (slot.exec != nullptr) cudaGraphExecDestroy(slot.exec);
    slot.exec = nullptr;
    const cudaError_t made = cudaGraphInstantiate(&slot.exec, graph, 0);
    cudaGraphDestroy(graph);
    MESHD_CUDA_CHECK(made);
  } else {
    cudaGraphDestroy(graph);
  }
  slot.shape = std::move(shape);
  slot.key = key;
}

ReplayGraph::Shape ReplayGraph::shape_of(cudaGraph_t graph) {
  size_t count = 0;
  MESHD_CUDA_CHECK(cudaGraphGetNodes(graph, nullptr, &count));
  std::vector<cudaGraphNode_t> nodes(count);
  MESHD_CUDA_CHECK(cudaGraphGetNodes(graph, nodes.data(), &count));
  Shape shape;
  for (cudaGraphNode_t node : nodes) {
    cudaGraphNodeType type{};
    MESHD_CUDA_CHECK(cudaGraphNodeGetType(node, &type));
    shape.push_back(static_cast<uintptr_t>(type));
    if (type == cudaGraphNodeTypeKernel) {
      cudaKernelNodeParams params{};
      MESHD_CUDA_CHECK(cudaGraphKernelNodeGetParams(node, &params));
      shape.push_back(reinterpret_cast<uintptr_t>(params.func));
    }
  }
  return shape;
}

}  // namespace meshd::gpu
