#include "core/delaunay/lawson_repair.h"

#include <utility>

#include "core/delaunay/exact_predicates.h"

namespace meshd {
namespace {

// Index of `value` in triangle t's neighbour list.
int slot_of(const std::array<int32_t, 3>& neighbors, int32_t value) {
  return neighbors[0] == value ? 0 : (neighbors[1] == value ? 1 : 2);
}

}  // namespace

RepairResult lawson_repair(const std::vector<Vec2>& points, const std::vector<char>& keep,
                           const std::vector<char>& on_boundary, Triangulation& tri) {
  RepairResult result;
  std::vector<char> drop(tri.triangles.size(), 0);
  for (size_t i = 0; i < tri.triangles.size(); ++i) {
    const auto& t = tri.triangles[i];
    if (orientation_sign(points[t[0]], points[t[1]], points[t[2]]) > 0) continue;
    if (keep[i] && !(on_boundary[t[0]] && on_boundary[t[1]] && on_boundary[t[2]])) return result;
    drop[i] = 1;
    ++result.dropped;
  }
  if (result.dropped > 0) drop_triangles(tri, drop);
  auto& T = tri.triangles;
  auto& N = tri.neighbors;

  // (triangle, slot) pairs whose opposite edge may fail the in-circle test. Entries can go stale
  // after flips; they then name another edge of that triangle, which is merely checked again.
  std::vector<std::pair<int32_t, int>> stack;
  stack.reserve(3 * T.size() / 2);
  for (size_t t = 0; t < T.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (N[t][k] > static_cast<int32_t>(t)) stack.emplace_back(static_cast<int32_t>(t), k);

  result.ok = true;
  int64_t& flips = result.flips;
  while (!stack.empty()) {
    const auto [t, k] = stack.back();
    stack.pop_back();
    const int32_t u = N[t][k];
    if (u < 0) continue;
    const int j = slot_of(N[u], t);
    // t = [a, b, c] counter-clockwise with a opposite the shared edge; u = [d, c, b].
    const int32_t a = T[t][k], b = T[t][(k + 1) % 3], c = T[t][(k + 2) % 3], d = T[u][j];
    if (in_circle_sign(points[a], points[b], points[c], points[d]) <= 0) continue;
    // Flip bc to ad: t' = [a, b, d], u' = [a, d, c].
    const int32_t n_ab = N[t][(k + 2) % 3], n_ca = N[t][(k + 1) % 3];
    const int32_t n_bd = N[u][(j + 1) % 3], n_dc = N[u][(j + 2) % 3];
    T[t] = {a, b, d};
    N[t] = {n_bd, u, n_ab};
    T[u] = {a, d, c};
    N[u] = {n_dc, n_ca, t};
    if (n_bd >= 0) N[n_bd][slot_of(N[n_bd], u)] = t;
    if (n_ca >= 0) N[n_ca][slot_of(N[n_ca], t)] = u;
    ++flips;
    stack.emplace_back(t, 0);
    stack.emplace_back(t, 2);
    stack.emplace_back(u, 0);
    stack.emplace_back(u, 1);
  }
  return result;
}

}  // namespace meshd
