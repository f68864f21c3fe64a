// keep_triangles.h: a scan of the flags, the compaction, the copy back; up to kOneBlockRows
// triangles (launch.h), all three in one launch of one block (one_block.cuh), since most of a small
// job's repairs drop a sliver or two.
#include "kernels/cuda_check.h"
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"
#include "kernels/triangle_compaction.cuh"

namespace meshd::gpu {
namespace {

__global__ void __launch_bounds__(kOneBlockThreads)
    keep_in_one_block(DeviceSpan<const uint8_t> keep, DeviceSpan<Tri> tris, DeviceSpan<Tri> nbrs,
                      DeviceSpan<int32_t> position, DeviceSpan<Tri> tris_out,
                      DeviceSpan<Tri> nbrs_out) {
  compact_in_block(keep, tris, nbrs, position, tris_out, nbrs_out);
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
    keep_in_one_block<<<1, kOneBlockThreads, 0, stream>>>(keep, tris.span(), nbrs.span(),
                                                          scratch.position.span(),
                                                          scratch.tris.span(), scratch.nbrs.span());
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
