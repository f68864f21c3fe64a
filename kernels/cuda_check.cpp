#include "kernels/cuda_check.h"

#include <string>

#include "core/common/error.h"

namespace meshd::gpu {

void throw_cuda_error(cudaError_t error, const char* call, const char* file, int line) {
  cudaGetLastError();  // clear a sticky-free error so that the next job starts clean
  const ErrorCode code =
      error == cudaErrorMemoryAllocation ? ErrorCode::kResourceExhausted : ErrorCode::kInternal;
  throw Error(code, "",
              std::string("CUDA ") + cudaGetErrorName(error) + " (" + cudaGetErrorString(error) +
                  ") in " + call + " at " + file + ":" + std::to_string(line));
}

int checked_device(int device) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    count = 0;
  }
  if (device < 0 || device >= count) {
    throw Error(
        ErrorCode::kUnavailable, "",
        "no CUDA device " + std::to_string(device) + " (" + std::to_string(count) + " visible)");
  }
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  return device;
}

namespace {
thread_local bool capturing = false;
}  // namespace

CaptureScope::CaptureScope() { capturing = true; }
CaptureScope::~CaptureScope() { capturing = false; }

void check_launch(const char* kernel, const char* file, int line) {
  cudaError_t error = cudaGetLastError();
#ifdef MESHD_CUDA_SYNC_LAUNCHES
  if (error == cudaSuccess && !capturing) error = cudaDeviceSynchronize();
#endif
  if (error != cudaSuccess) throw_cuda_error(error, kernel, file, line);
}

}  // namespace meshd::gpu
