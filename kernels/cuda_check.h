// The one checking macro for CUDA runtime calls, and the launch check that follows every kernel.
// Errors become meshd::Error with file:line and CUDA's error name: out-of-memory is
// RESOURCE_EXHAUSTED (the job fails, the server stays up), anything else INTERNAL.
#pragma once

#include <cuda_runtime.h>

namespace meshd::gpu {

[[noreturn]] void throw_cuda_error(cudaError_t error, const char* call, const char* file, int line);

// Makes `device` this thread's current device and returns it; throws Error(kUnavailable) when
// no such device is visible.
int checked_device(int device);

// Synchronise after every launch when MESHD_CUDA_SYNC_LAUNCHES is set (Debug builds define it),
// so that an error names the kernel that caused it.
void check_launch(const char* kernel, const char* file, int line);

// While one lives, this thread is capturing a CUDA graph: launch checks do not synchronise
// (capture forbids it; the graph's launch is checked instead).
class CaptureScope {
 public:
  CaptureScope();
  ~CaptureScope();
  CaptureScope(const CaptureScope&) = delete;
  CaptureScope& operator=(const CaptureScope&) = delete;
};

}  // namespace meshd::gpu

#define MESHD_CUDA_CHECK(call)                                               \
  do {                                                                       \
    const cudaError_t meshd_err_ = (call);                                   \
    if (meshd_err_ != cudaSuccess)                                           \
      ::meshd::gpu::throw_cuda_error(meshd_err_, #call, __FILE__, __LINE__); \
  } while (0)

#define MESHD_CHECK_LAUNCH(kernel) ::meshd::gpu::check_launch(kernel, __FILE__, __LINE__)
