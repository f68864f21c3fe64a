#include "core/delaunay/triangle_neighbors.h"

#include "core/mesh/edge_buckets.h"

namespace meshd {

bool triangle_neighbors(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                        std::vector<std::array<int32_t, 3>>& neighbors) {
  // The edge opposite vertex k of t runs from t[k+1] to t[k+2]: both uses of an edge meet in
  // the bucket of its smaller end.
  const EdgeBuckets b = bucket_half_edges(triangles, n, 1);
  neighbors.assign(triangles.size(), {-1, -1, -1});
  for (size_t v = 0; v < n; ++v) {
    for (int32_t i = b.start[v]; i < b.start[v + 1]; ++i) {
      int matches = 0;
      for (int32_t j = b.start[v]; j < b.start[v + 1]; ++j) {
        if (j == i || b.uses[j].far != b.uses[i].far) continue;
        if (++matches > 1 || ((b.uses[j].code ^ b.uses[i].code) & 1) == 0) return false;
        const int32_t id = b.uses[i].code >> 1;
        neighbors[id / 3][id % 3] = (b.uses[j].code >> 1) / 3;
      }
    }
  }
  return true;
}

}  // namespace meshd
