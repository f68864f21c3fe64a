#include "core/delaunay/triangle_neighbors.h"

#include <algorithm>

namespace meshd {

bool triangle_neighbors(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                        std::vector<std::array<int32_t, 3>>& neighbors) {
  // The edge opposite vertex k of t runs from t[k+1] to t[k+2]. A counting sort by the smaller
  // end puts both uses of an edge into one bucket of a handful of records, where they meet.
  const size_t m = triangles.size();
  std::vector<int64_t> start(n + 1, 0);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) ++start[std::min(t[(k + 1) % 3], t[(k + 2) % 3]) + 1];
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  struct Use {
    int32_t far;   // the larger end
    bool forward;  // runs from the smaller end to the larger
    int64_t id;    // 3 t + k
  };
  std::vector<Use> uses(3 * m);
  std::vector<int64_t> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = triangles[t][(k + 1) % 3], b = triangles[t][(k + 2) % 3];
      uses[fill[std::min(a, b)]++] = {std::max(a, b), a < b, static_cast<int64_t>(3 * t + k)};
    }
  }
  neighbors.assign(m, {-1, -1, -1});
  for (size_t v = 0; v < n; ++v) {
    for (int64_t i = start[v]; i < start[v + 1]; ++i) {
      int matches = 0;
      for (int64_t j = start[v]; j < start[v + 1]; ++j) {
        if (j == i || uses[j].far != uses[i].far) continue;
        if (++matches > 1 || uses[j].forward == uses[i].forward) return false;
        neighbors[uses[i].id / 3][uses[i].id % 3] = static_cast<int32_t>(uses[j].id / 3);
      }
    }
  }
  return true;
}

}  // namespace meshd
