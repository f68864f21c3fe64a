#include "core/distmesh/spatial_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace meshd {
namespace {

constexpr int kHilbertBits = 16;  // a 65,536 x 65,536 grid: far finer than any node spacing
constexpr uint32_t kCells = 1u << kHilbertBits;

// Distance of cell (x, y) along the Hilbert curve of order kHilbertBits (the classic rotate
// and flip per level, from the coarsest quadrant down).
uint64_t hilbert_index(uint32_t x, uint32_t y) {
  uint64_t d = 0;
  for (uint32_t s = 1u << (kHilbertBits - 1); s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0;
    const uint32_t ry = (y & s) ? 1 : 0;
    d += static_cast<uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant so that the curve's pieces join up
      if (rx == 1) {  // flipping every bit flips the lower ones, which the next levels read
        x = kCells - 1 - x;
        y = kCells - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

void hilbert_order(std::vector<Vec2>& points, int32_t first_free,
                   std::vector<std::array<int32_t, 3>>& triangles) {
  const auto n = static_cast<int32_t>(points.size());
  if (n - first_free < 2) return;
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (int32_t i = first_free; i < n; ++i) {
    lo = {std::min(lo.x, points[i].x), std::min(lo.y, points[i].y)};
    hi = {std::max(hi.x, points[i].x), std::max(hi.y, points[i].y)};
  }
  // One scale for both axes keeps the curve's cells square.
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  const double scale = extent > 0.0 ? (kCells - 1) / extent : 0.0;
  auto cell = [&](double v, double origin) {
    return static_cast<uint32_t>(std::clamp((v - origin) * scale, 0.0, kCells - 1.0));
  };
  std::vector<uint64_t> key(n);
  for (int32_t i = first_free; i < n; ++i)
    key[i] = hilbert_index(cell(points[i].x, lo.x), cell(points[i].y, lo.y));
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
