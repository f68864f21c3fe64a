#include "core/delaunay/triangle_neighbors.h"

#include <algorithm>

namespace meshd {

bool triangle_neighbors(const std::vector<std::array<int32_t, 3>>& triangles, size_t n,
                        std::vector<std::array<int32_t, 3>>& neighbors) {
  // The edge opposite vertex k of t runs from t[k+1] to t[k+2]. A counting sort by the smaller
  // end puts both uses of an edge into one bucket of a handful of records, where they meet.
  const size_t m = triangles.size();
  std::vector<int32_t> start(n + 1, 0);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) ++start[std::min(t[(k + 1) % 3], t[(k + 2) % 3]) + 1];
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  // Eight bytes a use, to keep the scattered writes few at millions of triangles.
  struct Use {
    int32_t far;   // the larger end
    int32_t code;  // 2 (3 t + k) + whether it runs from the smaller end to the larger
  };
  std::vector<Use> uses(3 * m);
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = triangles[t][(k + 1) % 3], b = triangles[t][(k + 2) % 3];
      uses[fill[std::min(a, b)]++] = {std::max(a, b),
                                      static_cast<int32_t>(2 * (3 * t + k)) | (a < b)};
    }
  }
  neighbors.assign(m, {-1, -1, -1});
  for (size_t v = 0; v < n; ++v) {
    for (int32_t i = start[v]; i < start[v + 1]; ++i) {
      int matches = 0;
      for (int32_t j = start[v]; j < start[v + 1]; ++j) {
        if (j == i || uses[j].far != uses[i].far) continue;
        if (++matches > 1 || ((uses[j].code ^ uses[i].code) & 1) == 0) return false;
        const int32_t id = uses[i].code >> 1;
        neighbors[id / 3][id % 3] = (uses[j].code >> 1) / 3;
      }
    }
  }
  return true;
}

}  // namespace meshd
