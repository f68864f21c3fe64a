// The CUDA devices this process sees, and what the server asks of them: how many, their names,
// memory and bandwidth, and the process's settings for many engines at once.
// A plain C++ header: g++ code includes it without CUDA.
#pragma once

#include <cstdint>
#include <string>

namespace meshd {

// Number of CUDA devices visible; 0 when there is no driver or no device.
int gpu_device_count();

// For a process that runs many engines at once (a server's GPU workers); before its first other
// CUDA call, for the first part to apply. Every kernel loads when a context is made, not at its
// first launch (unless CUDA_MODULE_LOADING says otherwise): CUDA loads a kernel lazily only once
// the device has no work in flight, and under load that waits for every other worker's job.
// Host threads that wait for their streams yield their cores between polls (CUDA spins when
// there are fewer contexts than cores), so that more workers than cores share the host.
void share_gpus_among_engines();
// Whether this process's kernels load when a context is made, and whether a thread waiting
// for `device` yields: what share_gpus_among_engines asks for, as CUDA reports it.
bool gpu_kernels_load_eagerly();
bool gpu_waits_yield(int device);
// "NVIDIA H100 80GB HBM3" and the like.
std::string gpu_device_name(int device);

// Bytes of `device`'s memory in use by every process (total less free), for the metrics.
int64_t gpu_memory_in_use(int device);

// Device-to-device copy bandwidth of `device` in GB/s, counting bytes read plus bytes written
// (a 512 MiB copy, median of 10 after a warm-up): the ceiling for bandwidth-bound steps.
double measure_copy_bandwidth(int device);

}  // namespace meshd
