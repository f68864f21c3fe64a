// The half-edges of a triangle set bucketed by their smaller end (a counting sort): all uses of
// one edge land in the bucket of that end, a handful of records, where matching them by the
// larger end takes linear time in all. The boundary of a triangle set (boundary.h) and the
// neighbours of a triangulation (triangle_neighbors.h) both match edges this way.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace meshd {

struct EdgeUse {
  int32_t far;   // the edge's larger end
  int32_t code;  // 2 (3 t + k), plus 1 when the half-edge runs from the smaller end to the larger
};

struct EdgeBuckets {
  std::vector<int32_t> start;  // #N + 1: the uses of bucket v are uses[start[v], start[v + 1])
  // #3M, eight bytes each: the scattered writes stay few. Not a vector: every entry is written
  // once, so zeroing them first would be a wasted pass over the largest array.
  std::unique_ptr<EdgeUse[]> uses;
};

// Half-edge 3 t + k runs from triangles[t][(k + shift) % 3] to triangles[t][(k + shift + 1) % 3].
// n: more than the largest point index. At most 2^30 / 3 triangles.
EdgeBuckets bucket_half_edges(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                              int shift);

}  // namespace meshd
