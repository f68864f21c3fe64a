// A run of launches replayed as one CUDA graph while everything it was captured with stays the
// same. A small job's retriangulation is a dozen launches of a few microseconds each: the host's
// calls, not the device, set its time. One graph launch replaces them once the run repeats.
//
// The caller names what the launches depend on (buffers' addresses and sizes, and a number that
// changes with any argument passed by value) as a key. A key seen for the first time runs the
// launches directly: that run grows any scratch they need, so that the next run with the same
// key captures the graph without allocating. Two of each are kept, for the two halves of a
// double-buffered argument (positions swapped after each step). Host code; one thread per object.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace meshd::gpu {

class ReplayGraph {
 public:
  using Key = std::vector<uint64_t>;
  using Body = std::function<void(cudaStream_t stream)>;

  ReplayGraph() = default;
  ~ReplayGraph();
  ReplayGraph(const ReplayGraph&) = delete;
  ReplayGraph& operator=(const ReplayGraph&) = delete;

  // Issues `body` on `stream`, directly or through its graph. `key` is called before the body
  // and, after a direct run, again, since that run may have moved the scratch it grew.
  void run(const std::function<Key()>& key, const Body& body, cudaStream_t stream);

  // Graph launches so far, for the tests.
  int64_t replays() const { return replays_; }

 private:
  // A graph's launches in order: each node's type, and a kernel node's function. An executable
  // graph takes an update only from a graph of the same shape.
  using Shape = std::vector<uintptr_t>;
  struct Slot {
    Key key;
    Shape shape;
    cudaGraphExec_t exec = nullptr;
  };
  void capture(Slot& slot, const Key& key, const Body& body, cudaStream_t stream);
  static Shape shape_of(cudaGraph_t graph);

  Slot slots_[2];
  int next_slot_ = 0;
  Key direct_[2];  // the keys of the last two direct runs
  int next_direct_ = 0;
  int64_t replays_ = 0;
};

}  // namespace meshd::gpu
