#include "core/distmesh/spatial_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/distmesh/hilbert_curve.cuh"

namespace meshd {

void hilbert_order(std::vector<Vec2>& points, int32_t first_free,
                   std::vector<std::array<int32_t, 3>>& triangles) {
  const auto n = static_cast<int32_t>(points.size());
  if (n - first_free < 2) return;
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (int32_t i = first_free; i < n; ++i) {
    lo = {std::min(lo.x, points[i].x), std::min(lo.y, points[i].y)};
    hi = {std::max(hi.x, points[i].x), std::max(hi.y, points[i].y)};
  }
  const HilbertFrame frame = HilbertFrame::over(lo, hi);
  std::vector<uint32_t> key(n);
  for (int32_t i = first_free; i < n; ++i) key[i] = frame.key(points[i]);
  std::vector<int32_t> order(n - first_free);  // order[k]: the old index of new node first_free + k
  std::iota(order.begin(), order.end(), first_free);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return key[a] < key[b]; });

  std::vector<int32_t> new_index(n);
  std::iota(new_index.begin(), new_index.begin() + first_free, 0);
  std::vector<Vec2> sorted(points.begin(), points.begin() + first_free);
  sorted.reserve(n);
  for (int32_t k = 0; k < n - first_free; ++k) {
    new_index[order[k]] = first_free + k;
    sorted.push_back(points[order[k]]);
  }
  points = std::move(sorted);
  for (auto& t : triangles)
    for (int32_t& v : t) v = new_index[v];
}

}  // namespace meshd
