// The global index of the calling thread in a one-dimensional grid, as the kernels number their
// items.
#pragma once

#include <cstdint>

namespace meshd::gpu {

__device__ inline int64_t thread_index() {
  return blockIdx.x * static_cast<int64_t>(blockDim.x) + threadIdx.x;
}

}  // namespace meshd::gpu
