// A small triangulation's centroid filter and bars in one launch: the filter over a grid, then,
// in the last of its blocks to finish, the bars at the scan of their counts and their CSR by
// counting, phase after phase in one block with block barriers between them, by the rules the
// kernels one by one follow (centroid_rule.cuh, bar_rules.cuh), and so with the same bits. A
// small job rebuilds its bars a few dozen times, and one by one each build was a dozen launches
// of a few microseconds' work; with many small jobs on one device, their launches rather than
// their work had filled it. The filter keeps a grid: one block evaluating every centroid's
// distance took plate_with_holes' builds at 2k nodes from 65 to 103 us.
#include <algorithm>

#include "kernels/bar_rules.cuh"
#include "kernels/centroid_rule.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"
#include "kernels/one_block.cuh"

namespace meshd::gpu {
namespace {

__global__ void __launch_bounds__(kOneBlockThreads) filter_and_bars(OneBlockBars a) {
  const int64_t m = a.live != nullptr ? *a.live : a.tris.size, n = a.p.size;
  // The filter: a row a thread over the grid.
  const int64_t row = static_cast<int64_t>(blockIdx.x) * kOneBlockThreads + threadIdx.x;
  if (row < a.tris.size) {
    a.keep[row] = row < m && centroid_kept(a.filter, a.p, a.tris[row]);
    __threadfence();  // visible to the last block before its ticket is drawn
  }
  __syncthreads();
  __shared__ bool last;
  if (threadIdx.x == 0) {
    last = atomicAdd(a.ticket, 1u) == gridDim.x - 1;
    if (last) *a.ticket = 0;  // for the next launch on this stream
    __threadfence();          // the other blocks' rows read after their ticket, as grid.sync does
  }
  __syncthreads();
  if (!last) return;

  __shared__ StripeScanStorage scan;
  __shared__ int32_t degree[kOneBlockRows];  // n + 1 of them, counted up and then down
  for (int64_t i = threadIdx.x; i <= n; i += kOneBlockThreads) degree[i] = 0;

  // The kept triangles, counted.
  int32_t at[kOneBlockItems];
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j) at[j] = stripe_row(j) < m && a.keep[stripe_row(j)];
  const int32_t kept_count = scan_stripes(at, scan);
  __syncthreads();  // the scan's storage free again

  // The bars: each triangle's at the exclusive scan of their counts in row order, as write_bars
  // places them.
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    at[j] = stripe_row(j) < m ? bars_of(stripe_row(j), a.nbrs, a.keep) : 0;
  const int32_t bar_count = scan_stripes(at, scan);
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    if (stripe_row(j) < m) write_bars_of(stripe_row(j), a.tris, a.nbrs, a.keep, at[j], a.bars);
  if (threadIdx.x == 0) {
    a.totals[0] = bar_count;
    a.totals[1] = kept_count;
    if (a.host_totals != nullptr) {
      a.host_totals[0] = bar_count;
      a.host_totals[1] = kept_count;
    }
    if (a.host_counters != nullptr) *a.host_counters = *a.counters;
  }
  __syncthreads();

  // The CSR: degrees, their scan, each end placed by counting down, each row sorted.
#pragma unroll 4
  for (int32_t b = threadIdx.x; b < bar_count; b += kOneBlockThreads) {
    const Bar bar = a.bars[b];
    atomicAdd(&degree[bar.a], 1);
    atomicAdd(&degree[bar.b], 1);
  }
  __syncthreads();
  // The offsets: n + 1 of them, kOneBlockItems a thread in a row (the scan's blocked
  // arrangement).
  const int64_t first = static_cast<int64_t>(threadIdx.x) * kOneBlockItems;
  int32_t offset[kOneBlockItems];
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j) offset[j] = first + j <= n ? degree[first + j] : 0;
  OneBlockScan(scan.stripe[0]).ExclusiveSum(offset, offset);
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    if (first + j <= n) a.csr_offset[first + j] = offset[j];
  __syncthreads();
#pragma unroll 4
  for (int32_t k = threadIdx.x; k < 2 * bar_count; k += kOneBlockThreads) {
    const Bar bar = a.bars[k >> 1];
    const int32_t node = (k & 1) ? bar.b : bar.a;
    a.csr_entry[a.csr_offset[node] + atomicSub(&degree[node], 1) - 1] = k;
  }
  __syncthreads();
  for (int64_t i = threadIdx.x; i < n; i += kOneBlockThreads) {
    order_row(a.bars, a.csr_offset[i], a.csr_offset[i + 1], a.csr_entry, a.csr_other);
    a.p_old[i] = a.p[i];
  }
}

}  // namespace

void launch_filter_and_bars(const OneBlockBars& a, cudaStream_t stream) {
  const int64_t blocks =
      std::max<int64_t>(1, (a.tris.size + kOneBlockThreads - 1) / kOneBlockThreads);
  filter_and_bars<<<blocks, kOneBlockThreads, 0, stream>>>(a);
  MESHD_CHECK_LAUNCH("filter_and_bars");
}

}  // namespace meshd::gpu
