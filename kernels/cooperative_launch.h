// How many blocks of a kernel a device runs at once, and the cooperative launch of a grid that
// meets at grid barriers (which needs every block resident). Host code, for the .cu files that
// define such kernels.
#pragma once

#include <cuda_runtime.h>

#include <algorithm>
#include <climits>
#include <cstdint>

#include "kernels/cuda_check.h"

namespace meshd::gpu {

// Blocks of `block` threads of `kernel` that `device` runs at once, at most `per_sm_cap` per SM.
template <typename Kernel>
int64_t resident_blocks(Kernel kernel, int block, int device, int per_sm_cap = INT_MAX) {
  int per_sm = 0, sms = 0;
  MESHD_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, kernel, block, 0));
  MESHD_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
  return static_cast<int64_t>(std::min(per_sm, per_sm_cap)) * sms;
}

// The largest grid of `kernel` that `device` launches cooperatively; 0 where it cannot.
template <typename Kernel>
int64_t cooperative_blocks(Kernel kernel, int block, int device, int per_sm_cap = INT_MAX) {
  int cooperative = 0;
  MESHD_CUDA_CHECK(cudaDeviceGetAttribute(&cooperative, cudaDevAttrCooperativeLaunch, device));
  return cooperative ? resident_blocks(kernel, block, device, per_sm_cap) : 0;
}

// Launches `kernel`(arg) as one cooperative grid of `blocks` blocks of `block` threads.
template <typename Arg>
void launch_cooperative(void (*kernel)(Arg), int64_t blocks, int block, Arg arg,
                        cudaStream_t stream, const char* name) {
  void* args[] = {&arg};
  MESHD_CUDA_CHECK(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(kernel),
                                               static_cast<unsigned>(blocks), block, args, 0,
                                               stream));
  MESHD_CHECK_LAUNCH(name);
}

}  // namespace meshd::gpu
