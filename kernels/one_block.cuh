// The shape of the kernels that take a small triangulation (up to kOneBlockRows rows, launch.h)
// in one block: the repair (flip_round.cu), the compaction (keep_triangles.cu) and the bars
// (bars_in_one_block.cu). Rows go to threads in stripes (row j * kOneBlockThreads + thread), so
// that a warp's loads are adjacent and each thread's rows load together: a block is bound by the
// latency of its loads (rows in a row per thread, with one scan for them all, took 38 us a
// compaction at 2k nodes against 21).
#pragma once

#include <cub/block/block_scan.cuh>

#include "kernels/launch.h"

namespace meshd::gpu {

constexpr int kOneBlockThreads = 1024;
constexpr int kOneBlockItems = 8;  // rows a thread
static_assert(kOneBlockThreads * kOneBlockItems == kOneBlockRows);

// The row of this thread's stripe j.
__device__ inline int64_t stripe_row(int j) {
  return static_cast<int64_t>(j) * kOneBlockThreads + threadIdx.x;
}

// Warp scans: their storage is a word a warp, so that each stripe has its own.
using OneBlockScan = cub::BlockScan<int32_t, kOneBlockThreads, cub::BLOCK_SCAN_WARP_SCANS>;
struct StripeScanStorage {
  typename OneBlockScan::TempStorage stripe[kOneBlockItems];
};

// The exclusive sums of `at` (this thread's stripes' values) in row order, in place: one scan a
// stripe, each stripe after the ones before. Returns the total, to every thread. A second call on
// the same storage must follow a block barrier.
__device__ inline int32_t scan_stripes(int32_t (&at)[kOneBlockItems], StripeScanStorage& s) {
  int32_t stripe_total[kOneBlockItems];
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j)
    OneBlockScan(s.stripe[j]).ExclusiveSum(at[j], at[j], stripe_total[j]);
  int32_t before = 0;
#pragma unroll
  for (int j = 0; j < kOneBlockItems; ++j) {
    at[j] += before;
    before += stripe_total[j];
  }
  return before;
}

}  // namespace meshd::gpu
