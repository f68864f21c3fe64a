// Pinned host memory for the few scalars an engine reads from the device every step. With
// unified addressing (every 64-bit platform CUDA supports) a kernel may also write it directly,
// through the same pointer: what the host reads after its next wait then needs no copy.
#pragma once

#include <cuda_runtime.h>

#include "kernels/cuda_check.h"

namespace meshd::gpu {

template <typename T>
class PinnedValue {
 public:
  PinnedValue() { MESHD_CUDA_CHECK(cudaMallocHost(&ptr_, sizeof(T))); }
  ~PinnedValue() { cudaFreeHost(ptr_); }
  PinnedValue(const PinnedValue&) = delete;
  PinnedValue& operator=(const PinnedValue&) = delete;
  T* get() const { return ptr_; }

 private:
  T* ptr_ = nullptr;
};

}  // namespace meshd::gpu
