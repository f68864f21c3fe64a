// A view of device memory, trivially copyable, passed to kernels by value.
#pragma once

#include <cstdint>
#include <type_traits>

#include "core/common/hd.h"

namespace meshd::gpu {

template <typename T>
struct DeviceSpan {
  T* data;
  int64_t size;
  MESHD_HD T& operator[](int64_t i) const { return data[i]; }
  // A mutable view converts to a read-only one.
  template <typename U = T, typename = std::enable_if_t<!std::is_const_v<U>>>
  MESHD_HD operator DeviceSpan<const U>() const {
    return {data, size};
  }
};

}  // namespace meshd::gpu
