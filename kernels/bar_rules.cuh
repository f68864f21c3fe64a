// The per-item rules of the bars' build on the device, shared by its kernels one by one
// (topology.cu) and by its one-block form for small triangulations (bars_in_one_block.cu): which
// edges are bars, and the order of a node's row in the bars' CSR.
#pragma once

#include <climits>
#include <cstdint>

#include "kernels/launch.h"

namespace meshd::gpu {

// Edge (t, u) is a bar of t when u is higher or missing and either side is kept.
__device__ inline bool is_bar(int64_t t, int32_t u, DeviceSpan<const uint8_t> keep) {
  if (u >= 0 && u < t) return false;
  return keep[t] || (u >= 0 && keep[u]);
}

__device__ inline int bars_of(int64_t t, DeviceSpan<const Tri> nbrs,
                              DeviceSpan<const uint8_t> keep) {
  int c = 0;
  for (int k = 0; k < 3; ++k) c += is_bar(t, nbrs[t].v[k], keep);
  return c;
}

// Triangle t's bars from bars[at] on.
__device__ inline void write_bars_of(int64_t t, DeviceSpan<const Tri> tris,
                                     DeviceSpan<const Tri> nbrs, DeviceSpan<const uint8_t> keep,
                                     int32_t at, DeviceSpan<Bar> bars) {
  for (int k = 0; k < 3; ++k)
    if (is_bar(t, nbrs[t].v[k], keep))
      bars[at++] = Bar{tris[t].v[(k + 1) % 3], tris[t].v[(k + 2) % 3]};
}

// The far end of bar end e (2b + end).
__device__ inline int32_t far_end(DeviceSpan<const Bar> bars, int32_t e) {
  return (e & 1) ? bars[e >> 1].a : bars[e >> 1].b;
}

// A row of up to W entries sorted in registers (odd-even transposition: static indices), and
// each entry's far end.
template <int W>
__device__ void order_short_row(DeviceSpan<const Bar> bars, int32_t first, int32_t d,
                                DeviceSpan<int32_t> csr_entry, DeviceSpan<int32_t> other) {
  int32_t row[W];
#pragma unroll
  for (int j = 0; j < W; ++j) row[j] = j < d ? csr_entry[first + j] : INT_MAX;
#pragma unroll
  for (int pass = 0; pass < W; ++pass) {
#pragma unroll
    for (int j = pass % 2; j + 1 < W; j += 2) {
      const int32_t low = min(row[j], row[j + 1]);
      row[j + 1] = max(row[j], row[j + 1]);
      row[j] = low;
    }
  }
#pragma unroll
  for (int j = 0; j < W; ++j) {
    if (j < d) {
      csr_entry[first + j] = row[j];
      other[first + j] = far_end(bars, row[j]);
    }
  }
}

// The row csr_entry[first, last) sorted, and each entry's far end. Rows hold about six entries;
// a long one (a fixed corner's, a fan in an early triangulation) is sorted in place.
__device__ inline void order_row(DeviceSpan<const Bar> bars, int32_t first, int32_t last,
                                 DeviceSpan<int32_t> csr_entry, DeviceSpan<int32_t> other) {
  if (last - first <= 8) return order_short_row<8>(bars, first, last - first, csr_entry, other);
  if (last - first <= 16) return order_short_row<16>(bars, first, last - first, csr_entry, other);
  for (int32_t k = first + 1; k < last; ++k) {
    const int32_t e = csr_entry[k];
    int32_t j = k;
    for (; j > first && csr_entry[j - 1] > e; --j) csr_entry[j] = csr_entry[j - 1];
    csr_entry[j] = e;
  }
  for (int32_t k = first; k < last; ++k) other[k] = far_end(bars, csr_entry[k]);
}

}  // namespace meshd::gpu
