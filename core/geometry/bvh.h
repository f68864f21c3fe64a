// A bounding-volume hierarchy over ranges: the spatial index that lets the evaluator visit only
// the parts of a geometry near a query point (the edges of a long polygon, the operands of a
// union of many shapes) while returning the same distance as visiting them all.
//
// Invariants: nodes live in one flat array (Program::nodes) so that the device reads them as it
// reads the code. A leaf covers the half-open range [first, last) of whatever its owner indexes
// (a polygon's edges, a union's instructions); an inner node has exactly two children, and its
// box holds both of theirs. A tree built here is at most kMaxBvhDepth levels deep (median
// splits halve the leaves), so a traversal stack of kMaxBvhDepth + 1 entries never overflows.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

constexpr int kMaxBvhDepth = 32;

struct BvhNode {
  Box box;
  uint32_t first;  // leaf: range [first, last); inner: index of the left child
  uint32_t last;   // leaf: range end; inner: index of the right child
  uint32_t leaf;   // 1 for a leaf
  uint32_t unused = 0;
};

// Squared distance from p to the box (0 inside it).
MESHD_HD inline double box_distance2(const Box& b, Vec2 p) {
  const double dx = p.x < b.min.x ? b.min.x - p.x : (p.x > b.max.x ? p.x - b.max.x : 0.0);
  const double dy = p.y < b.min.y ? b.min.y - p.y : (p.y > b.max.y ? p.y - b.max.y : 0.0);
  return dx * dx + dy * dy;
}

// One item of a tree to build: its box and the range a leaf over it covers.
struct BvhItem {
  Box box;
  uint32_t first;
  uint32_t last;
};

// Appends a tree over `items` (one leaf each, at least one item) to `nodes` and returns the
// index of its root. Leaves are grouped by median splits of their boxes' centres along the
// wider axis of those centres.
uint32_t build_bvh(std::vector<BvhItem> items, std::vector<BvhNode>& nodes);

}  // namespace meshd
