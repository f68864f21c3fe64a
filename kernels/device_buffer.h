// The one owner of device memory: a grow-only buffer. Kernels never see it, only DeviceSpan
// views passed by value. Capacity is kept between jobs (the engine's arena): a job no larger
// than the largest seen so far allocates nothing.
#pragma once

#include <cuda_runtime.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "kernels/cuda_check.h"
#include "kernels/device_span.cuh"

namespace meshd::gpu {

// Process-wide allocation counters, for the arena's tests and the metrics.
struct AllocationStats {
  static std::atomic<int64_t>& mallocs() {
    static std::atomic<int64_t> n{0};
    return n;
  }
  static std::atomic<int64_t>& bytes() {
    static std::atomic<int64_t> n{0};
    return n;
  }
};

template <typename T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  ~DeviceBuffer() { release(); }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  DeviceBuffer(DeviceBuffer&& o) noexcept { *this = std::move(o); }
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    std::swap(ptr_, o.ptr_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    return *this;
  }

  // Sets the size to n, growing the allocation (by at least 1.5x) when it is too small. The
  // contents are not preserved across a growth.
  void resize(size_t n) {
    if (n > capacity_) {
      release();
      const size_t cap = std::max(n, capacity_ + capacity_ / 2);
      MESHD_CUDA_CHECK(cudaMalloc(&ptr_, cap * sizeof(T)));
      capacity_ = cap;
      AllocationStats::mallocs()++;
      AllocationStats::bytes() += static_cast<int64_t>(cap * sizeof(T));
    }
    size_ = n;
  }

  // Grows the allocation to hold n, keeping the size and the contents.
  void reserve(size_t n, cudaStream_t stream) {
    if (n <= capacity_) return;
    DeviceBuffer grown;
    grown.resize(n);
    grown.size_ = size_;
    if (size_ > 0)
      MESHD_CUDA_CHECK(
          cudaMemcpyAsync(grown.ptr_, ptr_, size_ * sizeof(T), cudaMemcpyDeviceToDevice, stream));
    *this = std::move(grown);  // the old allocation is freed once the copy is done (cudaFree waits)
  }

  T* data() const { return ptr_; }
  size_t size() const { return size_; }
  DeviceSpan<T> span() const { return {ptr_, static_cast<int64_t>(size_)}; }

  void upload(const T* host, size_t n, cudaStream_t stream) {
    resize(n);
    if (n > 0)
      MESHD_CUDA_CHECK(cudaMemcpyAsync(ptr_, host, n * sizeof(T), cudaMemcpyHostToDevice, stream));
  }
  // A copy of `from` (resize, then a device-to-device copy): unlike a swap, each buffer keeps its
  // own capacity, so that the arena stays warm from one job to the next.
  void assign(const DeviceBuffer& from, cudaStream_t stream) {
    resize(from.size_);
    if (size_ > 0)
      MESHD_CUDA_CHECK(
          cudaMemcpyAsync(ptr_, from.ptr_, size_ * sizeof(T), cudaMemcpyDeviceToDevice, stream));
  }
  void download(T* host, cudaStream_t stream) const {
    if (size_ > 0)
      MESHD_CUDA_CHECK(
          cudaMemcpyAsync(host, ptr_, size_ * sizeof(T), cudaMemcpyDeviceToHost, stream));
  }

 private:
  void release() {
    if (ptr_ != nullptr) {
      cudaFree(ptr_);
      AllocationStats::bytes() -= static_cast<int64_t>(capacity_ * sizeof(T));
    }
    ptr_ = nullptr;
    capacity_ = 0;
    size_ = 0;
  }

  T* ptr_ = nullptr;
  size_t size_ = 0;
  size_t capacity_ = 0;
};

}  // namespace meshd::gpu
