#include "core/geometry/bvh.h"

#include <algorithm>
#include <cmath>

namespace meshd {
namespace {

Box hull(const Box& a, const Box& b) {
  return {{std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y)},
          {std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y)}};
}

Vec2 centre(const Box& b) {
  // Halves first: an unbounded side (a half-plane's infinite box) must not turn into NaN.
  return {0.5 * b.min.x + 0.5 * b.max.x, 0.5 * b.min.y + 0.5 * b.max.y};
}

// Builds the tree over items[begin, end) into nodes[at] and below.
void build(std::vector<BvhItem>& items, size_t begin, size_t end, uint32_t at,
           std::vector<BvhNode>& nodes) {
  if (end - begin == 1) {
    nodes[at] = {items[begin].box, items[begin].first, items[begin].last, 1};
    return;
  }
  Box spread{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
  for (size_t i = begin; i < end; ++i) {
    const Vec2 c = centre(items[i].box);
    spread = hull(spread, {c, c});
  }
  // An unbounded item's centre is infinite or NaN; comparing by a finite key keeps the order
  // strict weak either way.
  const bool by_x = !(spread.max.y - spread.min.y > spread.max.x - spread.min.x);
  auto key = [by_x](const BvhItem& it) {
    const Vec2 c = centre(it.box);
    const double k = by_x ? c.x : c.y;
    return std::isnan(k) ? 0.0 : k;
  };
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + static_cast<std::ptrdiff_t>(begin),
                   items.begin() + static_cast<std::ptrdiff_t>(mid),
                   items.begin() + static_cast<std::ptrdiff_t>(end),
                   [&](const BvhItem& a, const BvhItem& b) { return key(a) < key(b); });
  const auto left = static_cast<uint32_t>(nodes.size());
  nodes.resize(nodes.size() + 2);
  build(items, begin, mid, left, nodes);
  build(items, mid, end, left + 1, nodes);
  nodes[at] = {hull(nodes[left].box, nodes[left + 1].box), left, left + 1, 0};
}

}  // namespace

uint32_t build_bvh(std::vector<BvhItem> items, std::vector<BvhNode>& nodes) {
  const auto root = static_cast<uint32_t>(nodes.size());
  nodes.emplace_back();
  build(items, 0, items.size(), root, nodes);
  return root;
}

}  // namespace meshd
