// keep_triangles.h: a scan of the flags, the compaction, the copy back; up to kOneBlockRows
// triangles (launch.h), all three in one launch of one block, since most of a small job's repairs
// drop a sliver or two.
#include <cub/block/block_scan.cuh>

#include "kernels/cuda_check.h"
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"
#include "kernels/triangle_compaction.cuh"

namespace meshd::gpu {
namespace {

// Rows go to threads in stripes (row j * kThreads + thread), so that a warp's loads are adjacent:
// a block is bound by the latency of its loads (rows in a row per thread, one scan for them all,
// took 38 us a compaction at 2k nodes against 21).
constexpr int kThreads = 1024;
constexpr int kItems = 8;  // rows per thread
static_assert(kThreads * kItems == kOneBlockRows);

__global__ void __launch_bounds__(kThreads)
    keep_in_one_block(DeviceSpan<const uint8_t> keep, DeviceSpan<Tri> tris, DeviceSpan<Tri> nbrs,
                      DeviceSpan<int32_t> position, DeviceSpan<Tri> tris_out,
                      DeviceSpan<Tri> nbrs_out) {
  // Warp scans: their storage is a word a warp, so that each stripe can have its own.
  using BlockScan = cub::BlockScan<int32_t, kThreads, cub::BLOCK_SCAN_WARP_SCANS>;
  __shared__ typename BlockScan::TempStorage scan[kItems];
  const int64_t m = tris.size;
  const auto row = [](int j) { return static_cast<int64_t>(j) * kThreads + threadIdx.x; };
  // The scan in row order: one a stripe, each stripe after the ones before.
  int32_t at[kItems], stripe_total[kItems];
#pragma unroll
  for (int j = 0; j < kItems; ++j) at[j] = row(j) < m ? keep[row(j)] : 0;
#pragma unroll
  for (int j = 0; j < kItems; ++j) BlockScan(scan[j]).ExclusiveSum(at[j], at[j], stripe_total[j]);
  int32_t kept = 0;
#pragma unroll
  for (int j = 0; j < kItems; ++j) {
    if (row(j) < m) position[row(j)] = kept + at[j];
    kept += stripe_total[j];
  }
  __syncthreads();
#pragma unroll
  for (int j = 0; j < kItems; ++j)
    if (row(j) < m && keep[row(j)])
      compact_triangle(row(j), tris, nbrs, keep, position, tris_out, nbrs_out);
  __syncthreads();
  for (int64_t i = threadIdx.x; i < kept; i += kThreads) {
    tris[i] = tris_out[i];
    nbrs[i] = nbrs_out[i];
  }
}

}  // namespace

int64_t keep_triangles(DeviceSpan<const uint8_t> keep, DeviceBuffer<Tri>& tris,
                       DeviceBuffer<Tri>& nbrs, KeepScratch scratch, DeviceBuffer<uint8_t>& temp,
                       cudaStream_t stream, int64_t kept) {
  const auto m = static_cast<int64_t>(tris.size());
  scratch.position.resize(m);
  if (m > 0 && m <= kOneBlockRows) {
    scratch.tris.resize(m);
    scratch.nbrs.resize(m);
    keep_in_one_block<<<1, kThreads, 0, stream>>>(keep, tris.span(), nbrs.span(),
                                                  scratch.position.span(), scratch.tris.span(),
                                                  scratch.nbrs.span());
    MESHD_CHECK_LAUNCH("keep_in_one_block");
    if (kept < 0) kept = scan_total(scratch.position.data(), keep.data, m, stream);
    tris.resize(kept);  // the same memory, holding the kept triangles
    nbrs.resize(kept);
    return kept;
  }
  exclusive_scan(keep.data, scratch.position.data(), m, temp, stream);
  if (kept < 0) kept = scan_total(scratch.position.data(), keep.data, m, stream);
  scratch.tris.resize(kept);
  scratch.nbrs.resize(kept);
  launch_compact_triangles(tris.span(), nbrs.span(), keep, scratch.position.span(),
                           scratch.tris.span(), scratch.nbrs.span(), stream);
  tris.assign(scratch.tris, stream);
  nbrs.assign(scratch.nbrs, stream);
  return kept;
}

}  // namespace meshd::gpu
