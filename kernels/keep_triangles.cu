// keep_triangles.h: a scan of the flags, the compaction, the copy back.
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"

namespace meshd::gpu {

int64_t keep_triangles(DeviceSpan<const uint8_t> keep, DeviceBuffer<Tri>& tris,
                       DeviceBuffer<Tri>& nbrs, KeepScratch scratch, DeviceBuffer<uint8_t>& temp,
                       cudaStream_t stream, int64_t kept) {
  const auto m = static_cast<int64_t>(tris.size());
  scratch.position.resize(m);
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
