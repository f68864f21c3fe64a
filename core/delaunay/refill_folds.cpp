#include "core/delaunay/refill_folds.h"

#include <utility>

#include "core/delaunay/complete_triangulation.h"
#include "core/delaunay/exact_predicates.h"

namespace meshd {

bool cut_folds(const std::vector<Vec2>& points, Triangulation& tri) {
  std::vector<char> in_fold(points.size(), 0);
  bool folded = false;
  for (const auto& t : tri.triangles) {
    if (orientation_sign(points[t[0]], points[t[1]], points[t[2]]) > 0) continue;
    in_fold[t[0]] = in_fold[t[1]] = in_fold[t[2]] = 1;
    folded = true;
  }
  if (!folded) return false;
  // A triangle that still turns the right way can overlap the fold (the crossing node lies in
  // it), but only next to it: it shares a node with a turned-over triangle.
  std::vector<char> cut(tri.triangles.size(), 0);
  for (size_t t = 0; t < tri.triangles.size(); ++t) {
    const auto& v = tri.triangles[t];
    cut[t] = in_fold[v[0]] || in_fold[v[1]] || in_fold[v[2]];
  }
  drop_triangles(tri, cut);
  return true;
}

Triangulation refill_folds(const std::vector<Vec2>& points, Triangulation tri, int32_t always_gap) {
  if (!cut_folds(points, tri)) return {};
  return complete_triangulation(points, std::move(tri), always_gap);
}

}  // namespace meshd
