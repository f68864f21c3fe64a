// Device-wide scans and sorts through CUB, with temporary storage from the engine's arena.
#include <cub/block/block_scan.cuh>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>

#include "kernels/cuda_check.h"
#include "kernels/scan.h"

namespace meshd::gpu {

namespace {
// CUB's query of a scan's temporary storage is a dispatch of its own, about as costly on the host
// as the scan's: a job's scans repeat a few sizes between rebuilds, so the answers are kept, per
// thread (an engine's calls stay on its thread) and per device.
struct ScanBytes {
  int kind = -1, device = -1;
  int64_t n = -1;
  size_t bytes = 0;
};
template <typename Query>
size_t scan_bytes(int kind, int64_t n, Query query) {
  thread_local ScanBytes kept[8];
  thread_local int next = 0;
  int device = 0;
  MESHD_CUDA_CHECK(cudaGetDevice(&device));
  for (const ScanBytes& k : kept)
    if (k.kind == kind && k.device == device && k.n == n) return k.bytes;
  size_t bytes = 0;
  MESHD_CUDA_CHECK(query(bytes));
  kept[next] = {kind, device, n, bytes};
  next = (next + 1) % 8;
  return bytes;
}

// Up to one tile of items scans in one block: one launch, where CUB's device scan is two (its tile
// states' initialisation, then the scan), and a small job runs a few of them per repair. Over
// several tiles, one block's tiles one after the other cost what CUB's two launches do.
constexpr int kOneBlockThreads = 512;
constexpr int kOneBlockItems = 16;  // per thread
constexpr int64_t kOneBlockScanMax = kOneBlockThreads * kOneBlockItems;

template <typename In>
__global__ void __launch_bounds__(kOneBlockThreads)
    one_block_exclusive_scan(const In* in, int32_t* out, int64_t n) {
  using BlockScan = cub::BlockScan<int32_t, kOneBlockThreads>;
  __shared__ typename BlockScan::TempStorage scan;
  const int64_t first = static_cast<int64_t>(threadIdx.x) * kOneBlockItems;
  int32_t items[kOneBlockItems];
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    items[j] = first + j < n ? static_cast<int32_t>(in[first + j]) : 0;
  BlockScan(scan).ExclusiveSum(items, items);
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    if (first + j < n) out[first + j] = items[j];
}

// Whether n items scan in one block (launched); otherwise the caller runs CUB's device scan.
template <typename In>
bool scanned_in_one_block(const In* in, int32_t* out, int64_t n, cudaStream_t stream) {
  if (n > kOneBlockScanMax) return false;
  one_block_exclusive_scan<<<1, kOneBlockThreads, 0, stream>>>(in, out, n);
  MESHD_CHECK_LAUNCH("one_block_exclusive_scan");
  return true;
}
}  // namespace

void exclusive_scan(const int32_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream) {
  if (n == 0 || scanned_in_one_block(in, out, n, stream)) return;
  size_t bytes = scan_bytes(0, n, [&](size_t& b) {
    return cub::DeviceScan::ExclusiveSum(nullptr, b, in, out, n, stream);
  });
  temp.resize(std::max(bytes, temp.size()));
  MESHD_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp.data(), bytes, in, out, n, stream));
}

void exclusive_scan(const uint8_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream) {
  if (n == 0 || scanned_in_one_block(in, out, n, stream)) return;
  size_t bytes = scan_bytes(1, n, [&](size_t& b) {
    return cub::DeviceScan::ExclusiveScan(nullptr, b, in, out, cuda::std::plus<>{}, int32_t{0}, n,
                                          stream);
  });
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

template <typename Flag>
__global__ void write_scan_total(const int32_t* position, const Flag* flag, int64_t n,
                                 int64_t* total) {
  *total = n == 0 ? 0 : int64_t{position[n - 1]} + flag[n - 1];
}
template <typename Flag>
void launch_write_scan_total(const int32_t* position, const Flag* flag, int64_t n, int64_t* total,
                             cudaStream_t stream) {
  write_scan_total<<<1, 1, 0, stream>>>(position, flag, n, total);
  MESHD_CHECK_LAUNCH("write_scan_total");
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

void launch_scan_total(const int32_t* position, const uint8_t* flag, int64_t n, int64_t* total,
                       cudaStream_t stream) {
  launch_write_scan_total(position, flag, n, total, stream);
}
void launch_scan_total(const int32_t* position, const int32_t* flag, int64_t n, int64_t* total,
                       cudaStream_t stream) {
  launch_write_scan_total(position, flag, n, total, stream);
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
