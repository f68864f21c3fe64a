// Device-wide exclusive scans and a stable key-value radix sort (CUB): compaction, and the
// refinement's and the 3D repair's sorts. Temporary storage grows in `temp` and is kept between
// calls.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "kernels/device_buffer.h"

namespace meshd::gpu {

void exclusive_scan(const int32_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream);
void exclusive_scan(const uint8_t* in, int32_t* out, int64_t n, DeviceBuffer<uint8_t>& temp,
                    cudaStream_t stream);
// The total of an exclusive scan of n flags (or counts): position[n - 1] + flag[n - 1], read
// back to the host (which waits for the stream); 0 for n = 0.
int64_t scan_total(const int32_t* position, const uint8_t* flag, int64_t n, cudaStream_t stream);
int64_t scan_total(const int32_t* position, const int32_t* flag, int64_t n, cudaStream_t stream);
// The same total left on the device in *total, for a caller that reads several at once.
void launch_scan_total(const int32_t* position, const uint8_t* flag, int64_t n, int64_t* total,
                       cudaStream_t stream);
void launch_scan_total(const int32_t* position, const int32_t* flag, int64_t n, int64_t* total,
                       cudaStream_t stream);
// Stable: equal keys keep the order of values_in, which keeps the output deterministic.
void sort_pairs(const int32_t* keys_in, int32_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream);
void sort_pairs(const uint32_t* keys_in, uint32_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream);
void sort_pairs(const uint64_t* keys_in, uint64_t* keys_out, const int32_t* values_in,
                int32_t* values_out, int64_t n, int end_bit, DeviceBuffer<uint8_t>& temp,
                cudaStream_t stream);

}  // namespace meshd::gpu
