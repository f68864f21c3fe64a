#include "core/mesh/boundary.h"

#include <algorithm>

#include "core/mesh/edge_buckets.h"

namespace meshd {

std::vector<int32_t> boundary_half_edges(const std::vector<std::array<int32_t, 3>>& triangles) {
  // Half-edge 3 t + k runs from t[k] to t[k+1]; an edge is on the boundary when its bucket holds
  // no other use of it.
  int32_t top = -1;
  for (const auto& t : triangles) top = std::max({top, t[0], t[1], t[2]});
  const EdgeBuckets b = bucket_half_edges(triangles, static_cast<size_t>(top) + 1, 0);
  std::vector<int32_t> ids;
  for (size_t v = 0; v + 1 < b.start.size(); ++v) {
    for (int32_t i = b.start[v]; i < b.start[v + 1]; ++i) {
      int count = 0;
      for (int32_t j = b.start[v]; j < b.start[v + 1] && count < 2; ++j)
        count += b.uses[j].far == b.uses[i].far;
      if (count == 1) ids.push_back(b.uses[i].code >> 1);
    }
  }
  // A few thousand ids at a million triangles: sorting them beats a flag per half-edge, and the
  // result does not depend on the buckets' order.
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<std::array<int32_t, 2>> half_edge_ends(
    const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<int32_t>& ids) {
  std::vector<std::array<int32_t, 2>> edges;
  edges.reserve(ids.size());
  for (const int32_t id : ids) {
    const auto& t = triangles[id / 3];
    const int k = id % 3;
    edges.push_back({t[k], t[(k + 1) % 3]});
  }
  return edges;
}

std::vector<std::array<int32_t, 2>> boundary_edges_of(
    const std::vector<std::array<int32_t, 3>>& triangles) {
  return half_edge_ends(triangles, boundary_half_edges(triangles));
}

}  // namespace meshd
