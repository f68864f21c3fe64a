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

namespace {
template <typename Flag>
int64_t last_position_plus_flag(const int32_t* position, const Flag* flag, int64_t n,
                                cudaStream_t stream) {
  if (n == 0) return 0;
  int32_t at = 0;
  Flag last{};
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(&at, position + n - 1, sizeof(int32_t), cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(&last, flag + n - 1, sizeof(Flag), cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  return int64_t{at} + last;
}

template <typename Key>
void sort_key_pairs(const Key* keys_in, Key* keys_out, const int32_t* values_in,
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
}  // namespace

int64_t scan_total(const int32_t* position, const uint8_t* flag, int64_t n, cudaStream_t stream) {
  return last_position_plus_flag(position, flag, n, stream);
}
int64_t scan_total(const int32_t* position, const int32_t* flag, int64_t n, cudaStream_t stream) {
  return last_position_plus_flag(position, flag, n, stream);
}

void sort_pairs(const int32_t* keys_in, int32_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream) {
  sort_key_pairs(keys_in, keys_out, values_in, values_out, n, end_bit, temp, stream);
}
void sort_pairs(const uint32_t* keys_in, uint32_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream) {
  sort_key_pairs(keys_in, keys_out, values_in, values_out, n, end_bit, temp, stream);
}
void sort_pairs(const uint64_t* keys_in, uint64_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream) {
  sort_key_pairs(keys_in, keys_out, values_in, values_out, n, end_bit, temp, stream);
}

}  // namespace meshd::gpu
