// Device-wide scans and sorts through CUB, with temporary storage from the engine's arena.
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include "kernels/scan.h"

namespace meshd::gpu {

void exclusive_scan(const int32_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream) {
  if (n == 0) return;
  size_t bytes = 0;
  MESHD_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, n, stream));
  temp.resize(std::max(bytes, temp.size()));
  MESHD_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, in, out, n, stream));
}

void exclusive_scan(const uint8_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream) {
  if (n == 0) return;
  size_t bytes = 0;
  MESHD_CUDA_CHECK(cub::DeviceScan::ExclusiveScan(nullptr, bytes, in, out, cuda::std::plus<>{},
                                                  int32_t{0}, n, stream));
  temp.resize(std::max(bytes, temp.size()));
  MESHD_CUDA_CHECK(cub::DeviceScan::ExclusiveScan(temp.data(), bytes, in, out, cuda::std::plus<>{},
                                                  int32_t{0}, n, stream));
}

void sort_pairs(const int32_t* keys_in, int32_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream) {
  if (n == 0) return;
  size_t bytes = 0;
  MESHD_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys_in, keys_out, values_in,
                                                   values_out, n, 0, end_bit, stream));
  temp.resize(std::max(bytes, temp.size()));
  MESHD_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp.data(), bytes, keys_in, keys_out, values_in,
                                                   values_out, n, 0, end_bit, stream));
}

}  // namespace meshd::gpu
