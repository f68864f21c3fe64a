#include "core/mesh/boundary.h"

#include <algorithm>

namespace meshd {

std::vector<std::array<int32_t, 2>> boundary_edges_of(
    const std::vector<std::array<int32_t, 3>>& triangles) {
  // One record per half-edge: the undirected key (smaller index in the high word) and the
  // half-edge's id 3 t + k. Sorting groups the uses of each edge; a group of one is a boundary
  // edge. Sorting flat records beats a hash map by a wide margin at a million triangles.
  struct HalfEdge {
    uint64_t key;
    int64_t id;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<uint32_t>(triangles[t][k]);
      const auto b = static_cast<uint32_t>(triangles[t][(k + 1) % 3]);
      const uint64_t key = (uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      half_edges.push_back({key, static_cast<int64_t>(3 * t + k)});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key; });

  std::vector<int64_t> boundary_ids;
  for (size_t i = 0; i < half_edges.size();) {
    size_t j = i + 1;
    while (j < half_edges.size() && half_edges[j].key == half_edges[i].key) ++j;
    if (j - i == 1) boundary_ids.push_back(half_edges[i].id);
    i = j;
  }
  // Back to triangle order, so the result does not depend on the sort's tie-breaking.
  std::sort(boundary_ids.begin(), boundary_ids.end());

  std::vector<std::array<int32_t, 2>> edges;
  edges.reserve(boundary_ids.size());
  for (const int64_t id : boundary_ids) {
    const auto& t = triangles[id / 3];
    const int k = static_cast<int>(id % 3);
    edges.push_back({t[k], t[(k + 1) % 3]});
  }
  return edges;
}

}  // namespace meshd
