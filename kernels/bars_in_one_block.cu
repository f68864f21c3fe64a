// The bars of a small triangulation, once the centroid filter has run, in one launch: the bars at
// the scan of their counts, and their CSR by counting, phase after phase in one block with block
// barriers between them, by the rules the kernels one by one follow (bar_rules.cuh), and so with
// the same bits. A small job rebuilds its bars a few dozen times, and one by one each build was a
// dozen launches of a few microseconds' work; with many small jobs on one device, their launches
// rather than their work had filled it. The filter keeps a grid of its own: one block evaluating
// every centroid's distance took plate_with_holes' builds at 2k nodes from 65 to 103 us.
#include <cub/block/block_scan.cuh>

#include "kernels/bar_rules.cuh"
#include "kernels/cuda_check.h"
#include "kernels/launch.h"

namespace meshd::gpu {
namespace {

// Items go to threads in stripes (item j * kThreads + thread), so that a warp's loads are
// adjacent, and each thread's items load together: a block is bound by the latency of its loads.
constexpr int kThreads = 1024;
constexpr int kItems = 8;  // rows per thread
static_assert(kThreads * kItems == kOneBlockRows);

__global__ void __launch_bounds__(kThreads) bars_in_one_block(OneBlockBars a) {
  // Warp scans: their storage is a word a warp, so that each stripe can have its own.
  using BlockScan = cub::BlockScan<int32_t, kThreads, cub::BLOCK_SCAN_WARP_SCANS>;
  __shared__ typename BlockScan::TempStorage scan[kItems];
  __shared__ int32_t degree[kOneBlockRows];  // n + 1 of them, counted up and then down
  __shared__ int32_t kept_count;
  const int64_t m = a.tris.size, n = a.p.size;
  const auto row = [](int j) { return static_cast<int64_t>(j) * kThreads + threadIdx.x; };

  // The kept triangles, counted.
  if (threadIdx.x == 0) kept_count = 0;
  for (int64_t i = threadIdx.x; i <= n; i += kThreads) degree[i] = 0;
  __syncthreads();
  int32_t kept = 0;
#pragma unroll
  for (int j = 0; j < kItems; ++j) kept += row(j) < m && a.keep[row(j)];
  atomicAdd(&kept_count, kept);
  __syncthreads();  // kept_count whole before thread 0 reads it below

  // The bars: each triangle's at the exclusive scan of their counts in row order, as write_bars
  // places them; one scan a stripe, each stripe after the ones before.
  int32_t at[kItems], stripe_total[kItems];
#pragma unroll
  for (int j = 0; j < kItems; ++j) at[j] = row(j) < m ? bars_of(row(j), a.nbrs, a.keep) : 0;
#pragma unroll
  for (int j = 0; j < kItems; ++j) BlockScan(scan[j]).ExclusiveSum(at[j], at[j], stripe_total[j]);
  int32_t bar_count = 0;
#pragma unroll
  for (int j = 0; j < kItems; ++j) {
    if (row(j) < m) write_bars_of(row(j), a.tris, a.nbrs, a.keep, bar_count + at[j], a.bars);
    bar_count += stripe_total[j];
  }
  if (threadIdx.x == 0) {
    a.totals[0] = bar_count;
    a.totals[1] = kept_count;
  }
  __syncthreads();

  // The CSR: degrees, their scan, each end placed by counting down, each row sorted.
#pragma unroll 4
  for (int32_t b = threadIdx.x; b < bar_count; b += kThreads) {
    const Bar bar = a.bars[b];
    atomicAdd(&degree[bar.a], 1);
    atomicAdd(&degree[bar.b], 1);
  }
  __syncthreads();
  // The offsets: n + 1 of them, kItems a thread in a row (the scan's blocked arrangement).
  const int64_t first = static_cast<int64_t>(threadIdx.x) * kItems;
  int32_t offset[kItems];
#pragma unroll
  for (int j = 0; j < kItems; ++j) offset[j] = first + j <= n ? degree[first + j] : 0;
  BlockScan(scan[0]).ExclusiveSum(offset, offset);
#pragma unroll
  for (int j = 0; j < kItems; ++j)
    if (first + j <= n) a.csr_offset[first + j] = offset[j];
  __syncthreads();
#pragma unroll 4
  for (int32_t k = threadIdx.x; k < 2 * bar_count; k += kThreads) {
    const Bar bar = a.bars[k >> 1];
    const int32_t node = (k & 1) ? bar.b : bar.a;
    a.csr_entry[a.csr_offset[node] + atomicSub(&degree[node], 1) - 1] = k;
  }
  __syncthreads();
  for (int64_t i = threadIdx.x; i < n; i += kThreads) {
    order_row(a.bars, a.csr_offset[i], a.csr_offset[i + 1], a.csr_entry, a.csr_other);
    a.p_old[i] = a.p[i];
  }
}

}  // namespace

void launch_bars_in_one_block(const OneBlockBars& a, cudaStream_t stream) {
  bars_in_one_block<<<1, kThreads, 0, stream>>>(a);
  MESHD_CHECK_LAUNCH("bars_in_one_block");
}

}  // namespace meshd::gpu
