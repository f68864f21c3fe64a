#include "core/geometry/shape.h"

#include <algorithm>
#include <cmath>

namespace meshd {

Vec2 apply(const Similarity& t, Vec2 p) {
  const double c = std::cos(t.angle), s = std::sin(t.angle);
  return {t.scale * (c * p.x - s * p.y) + t.offset.x, t.scale * (s * p.x + c * p.y) + t.offset.y};
}

Similarity compose(const Similarity& outer, const Similarity& inner) {
  // outer(inner(p)) = so R(ao) (si R(ai) p + ti) + to
  Similarity t;
  t.scale = outer.scale * inner.scale;
  t.angle = outer.angle + inner.angle;
  t.offset = apply(outer, inner.offset);
  return t;
}

namespace {
template <typename Fn>
int fold_children(const Shape& shape, int leaf, Fn fn) {
  if (const auto* csg = std::get_if<Csg>(&shape.node)) {
    int acc = 0;
    for (const Shape& child : csg->operands) acc = fn(acc, child);
    return acc;
  }
  if (const auto* tr = std::get_if<Transformed>(&shape.node)) {
    int acc = 0;
    for (const Shape& child : tr->operand) acc = fn(acc, child);
    return acc;
  }
  return leaf;
}
}  // namespace

int tree_depth(const Shape& shape) {
  const int below = fold_children(
      shape, 0, [](int acc, const Shape& child) { return std::max(acc, tree_depth(child)); });
  return below + 1;
}

int tree_size(const Shape& shape) {
  return 1 + fold_children(shape, 0,
                           [](int acc, const Shape& child) { return acc + tree_size(child); });
}

}  // namespace meshd
