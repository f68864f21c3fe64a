#include "kernels/gpu_devices.h"

#include <cuda.h>
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "core/common/error.h"
#include "kernels/device_buffer.h"

namespace meshd {

using gpu::DeviceBuffer;

int gpu_device_count() {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

void share_gpus_among_engines() {
  setenv("CUDA_MODULE_LOADING", "EAGER", /*overwrite=*/0);
  const int devices = gpu_device_count();
  for (int d = 0; d < devices; ++d) {
    MESHD_CUDA_CHECK(cudaSetDevice(d));
    MESHD_CUDA_CHECK(cudaSetDeviceFlags(cudaDeviceScheduleYield));
  }
}

bool gpu_kernels_load_eagerly() {
  // A driver call: the runtime does not report the loading mode.
  using LoadingMode = CUresult (*)(CUmoduleLoadingMode*);
  void* entry = nullptr;
  cudaDriverEntryPointQueryResult found{};
  MESHD_CUDA_CHECK(cudaGetDriverEntryPointByVersion("cuModuleGetLoadingMode", &entry, 12000,
                                                    cudaEnableDefault, &found));
  CUmoduleLoadingMode mode{};
  return found == cudaDriverEntryPointSuccess &&
         reinterpret_cast<LoadingMode>(entry)(&mode) == CUDA_SUCCESS &&
         mode == CU_MODULE_EAGER_LOADING;
}

bool gpu_waits_yield(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  unsigned flags = 0;
  MESHD_CUDA_CHECK(cudaGetDeviceFlags(&flags));
  return (flags & cudaDeviceScheduleMask) == cudaDeviceScheduleYield;
}

int64_t gpu_memory_in_use(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  size_t free = 0, total = 0;
  MESHD_CUDA_CHECK(cudaMemGetInfo(&free, &total));
  return static_cast<int64_t>(total - free);
}

std::string gpu_device_name(int device) {
  cudaDeviceProp prop{};
  MESHD_CUDA_CHECK(cudaGetDeviceProperties(&prop, device));
  return prop.name;
}

double measure_copy_bandwidth(int device) {
  MESHD_CUDA_CHECK(cudaSetDevice(device));
  constexpr size_t kBytes = size_t{512} << 20;
  DeviceBuffer<uint8_t> a, b;
  a.resize(kBytes);
  b.resize(kBytes);
  MESHD_CUDA_CHECK(cudaMemset(a.data(), 1, kBytes));
  cudaEvent_t start, stop;
  MESHD_CUDA_CHECK(cudaEventCreate(&start));
  MESHD_CUDA_CHECK(cudaEventCreate(&stop));
  std::vector<float> ms;
  for (int i = 0; i < 11; ++i) {
    MESHD_CUDA_CHECK(cudaEventRecord(start));
    MESHD_CUDA_CHECK(cudaMemcpy(b.data(), a.data(), kBytes, cudaMemcpyDeviceToDevice));
    MESHD_CUDA_CHECK(cudaEventRecord(stop));
    MESHD_CUDA_CHECK(cudaEventSynchronize(stop));
    float t = 0;
    MESHD_CUDA_CHECK(cudaEventElapsedTime(&t, start, stop));
    if (i > 0) ms.push_back(t);
  }
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  std::sort(ms.begin(), ms.end());
  return 2.0 * kBytes / (ms[ms.size() / 2] * 1e-3) / 1e9;
}

}  // namespace meshd
