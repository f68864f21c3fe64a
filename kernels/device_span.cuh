// A view of device memory, trivially copyable, passed to kernels by value. Built with
// MESHD_CHECKED_SPANS (CMake option of that name), every index is checked: one out of bounds
// prints itself and stops the kernel, which the host sees as a CUDA error at its next call.
#pragma once

#include <cstdint>
#ifdef MESHD_CHECKED_SPANS
#include <cstdio>
#include <cstdlib>
#endif
#include <type_traits>

#include "core/common/hd.h"

namespace meshd::gpu {

template <typename T>
struct DeviceSpan {
  T* data;
  int64_t size;
  MESHD_HD T& operator[](int64_t i) const {
#ifdef MESHD_CHECKED_SPANS
    if (i < 0 || i >= size) out_of_bounds(i);
#endif
    return data[i];
  }
  // A mutable view converts to a read-only one.
  template <typename U = T, typename = std::enable_if_t<!std::is_const_v<U>>>
  MESHD_HD operator DeviceSpan<const U>() const {
    return {data, size};
  }

#ifdef MESHD_CHECKED_SPANS
  MESHD_HD void out_of_bounds(int64_t i) const {
    printf("meshd: span index %lld out of bounds (size %lld)\n", static_cast<long long>(i),
           static_cast<long long>(size));
#ifdef __CUDA_ARCH__
    __trap();
#else
    std::abort();
#endif
  }
#endif
};

}  // namespace meshd::gpu
