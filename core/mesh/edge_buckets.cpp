#include "core/mesh/edge_buckets.h"

#include <algorithm>

namespace meshd {

EdgeBuckets bucket_half_edges(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                              int shift) {
  EdgeBuckets b;
  b.start.assign(n + 1, 0);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) ++b.start[std::min(t[k], t[(k + 1) % 3]) + 1];
  for (size_t v = 0; v < n; ++v) b.start[v + 1] += b.start[v];
  b.uses = std::make_unique_for_overwrite<EdgeUse[]>(3 * triangles.size());
  // start[v] serves as bucket v's fill cursor and ends at start[v + 1]'s value: one shift puts
  // it back, without a copy of the offsets.
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t from = triangles[t][(k + shift) % 3], to = triangles[t][(k + shift + 1) % 3];
      b.uses[b.start[std::min(from, to)]++] = {std::max(from, to),
                                               static_cast<int32_t>(2 * (3 * t + k)) | (from < to)};
    }
  }
  std::copy_backward(b.start.begin(), b.start.end() - 1, b.start.end());
  b.start[0] = 0;
  return b;
}

}  // namespace meshd
