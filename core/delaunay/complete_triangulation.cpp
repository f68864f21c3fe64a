#include "core/delaunay/complete_triangulation.h"

#include <unordered_map>
#include <utility>

#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/triangle_neighbors.h"

namespace meshd {
namespace {

// Retries after a failed check, each without the triangles next to a gap.
constexpr int kMaxErosions = 4;

// Appends the gaps' triangles to `out` (U's triangles and neighbours) and links them to U and
// to each other. Returns false, with `out` as it came, when a check fails.
bool fill_gaps(const std::vector<Vec2>& points, int32_t always_gap, Triangulation& out) {
  const size_t n = points.size();
  const size_t u_count = out.triangles.size();

  // The points that bound a gap: on U's boundary, in no triangle, or among the first
  // always_gap. U's boundary edges (walls), directed with U on their left, each with its use
  // 3 t + k in U.
  std::vector<char> in_u(n, 0), on_gap(n, 0);
  std::unordered_map<uint64_t, int64_t> walls;
  auto key = [](int32_t from, int32_t to) {
    return (uint64_t{static_cast<uint32_t>(from)} << 32) | static_cast<uint32_t>(to);
  };
  for (size_t t = 0; t < u_count; ++t) {
    for (int k = 0; k < 3; ++k) {
      in_u[out.triangles[t][k]] = 1;
      if (out.neighbors[t][k] >= 0) continue;
      const int32_t from = out.triangles[t][(k + 1) % 3], to = out.triangles[t][(k + 2) % 3];
      on_gap[from] = on_gap[to] = 1;
      walls.emplace(key(from, to), static_cast<int64_t>(3 * t + k));
    }
  }
  std::vector<int32_t> gap_index, local(n, -1);
  std::vector<Vec2> gap_points;
  for (size_t v = 0; v < n; ++v) {
    if (v < static_cast<size_t>(always_gap) || !in_u[v] || on_gap[v]) {
      local[v] = static_cast<int32_t>(gap_index.size());
      gap_index.push_back(static_cast<int32_t>(v));
      gap_points.push_back(points[v]);
    }
  }
  // The walls as constraints: a Delaunay edge of U need not be an edge of CGAL's Delaunay
  // triangulation of the gaps' points when those are co-circular (a hole's boundary nodes all
  // lie on its circle, and a dropped sliver there leaves walls that are chords of it).
  std::vector<std::array<int32_t, 2>> constraints;
  constraints.reserve(walls.size());
  for (const auto& w : walls)
    constraints.push_back({local[static_cast<int32_t>(w.first >> 32)],
                           local[static_cast<int32_t>(w.first & 0xffffffffu)]});
  const Triangulation gaps = constrained_delaunay_triangulate(gap_points, constraints);
  if (gaps.triangles.empty()) return false;

  // Which of its triangles fill gaps, found without geometry (gap triangles can be flat along a
  // lattice line, where no point test is safe): U's boundary edges are edges of this small
  // triangulation too; the triangle on their right is in a gap, and so is every triangle reached
  // from one without crossing them, or from a hull edge that does not bound U.
  const size_t mg = gaps.triangles.size();
  std::vector<char> in_gap(mg, 0);
  std::vector<int32_t> stack;
  int64_t hull_edges = 0, walls_seen = 0;
  auto global = [&](size_t t, int k) { return gap_index[gaps.triangles[t][k]]; };
  auto is_wall = [&](size_t t, int k) {
    const int32_t from = global(t, (k + 1) % 3), to = global(t, (k + 2) % 3);
    return walls.count(key(from, to)) + walls.count(key(to, from)) > 0;
  };
  for (size_t t = 0; t < mg; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t from = global(t, (k + 1) % 3), to = global(t, (k + 2) % 3);
      const bool u_left = walls.count(key(from, to)) > 0, u_right = walls.count(key(to, from)) > 0;
      walls_seen += u_left + u_right;
      hull_edges += gaps.neighbors[t][k] < 0;
      if ((u_right || (gaps.neighbors[t][k] < 0 && !u_left)) && !in_gap[t]) {
        in_gap[t] = 1;
        stack.push_back(static_cast<int32_t>(t));
      }
    }
  }
  // Every wall is met twice (once from each side) unless it lies on the hull.
  while (!stack.empty()) {
    const int32_t t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const int32_t u_t = gaps.neighbors[t][k];
      if (u_t < 0 || in_gap[u_t] || is_wall(t, k)) continue;
      in_gap[u_t] = 1;
      stack.push_back(u_t);
    }
  }
  int64_t walls_on_hull = 0;
  for (size_t t = 0; t < mg; ++t)
    for (int k = 0; k < 3; ++k) walls_on_hull += gaps.neighbors[t][k] < 0 && is_wall(t, k);
  if (walls_seen != 2 * static_cast<int64_t>(walls.size()) - walls_on_hull) return false;
  std::vector<int32_t> new_id(mg, -1);
  int64_t next_id = static_cast<int64_t>(u_count);
  for (size_t t = 0; t < mg; ++t) {
    if (!in_gap[t]) continue;
    const auto& g = gaps.triangles[t];
    if (orientation_sign(gap_points[g[0]], gap_points[g[1]], gap_points[g[2]]) <= 0) return false;
    new_id[t] = static_cast<int32_t>(next_id++);
  }
  // A triangulation of N points with H on the hull has 2 N - 2 - H triangles.
  if (next_id != 2 * static_cast<int64_t>(n) - 2 - hull_edges) return false;

  // The links, without a pass over all triangles. A gap triangle's edge borders another gap
  // triangle, or is a wall with U on the other side, or lies on the hull. With every triangle
  // counter-clockwise, U linked consistently and the open edges exactly the hull's, the
  // triangles cover the hull once: they form a triangulation.
  std::vector<std::array<int32_t, 3>> gap_neighbors;
  gap_neighbors.reserve(static_cast<size_t>(next_id) - u_count);
  std::vector<std::pair<int64_t, int32_t>> wall_links;  // U's use 3 t + k, gap triangle
  int64_t open_edges = walls_on_hull;
  for (size_t t = 0; t < mg; ++t) {
    if (!in_gap[t]) continue;
    std::array<int32_t, 3> nb{-1, -1, -1};
    for (int k = 0; k < 3; ++k) {
      const int32_t from = global(t, (k + 1) % 3), to = global(t, (k + 2) % 3);
      const int32_t u_t = gaps.neighbors[t][k];
      if (walls.count(key(from, to)) > 0) return false;  // a gap triangle on U's side
      const auto wall = walls.find(key(to, from));
      if (wall != walls.end()) {
        nb[k] = static_cast<int32_t>(wall->second / 3);
        wall_links.emplace_back(wall->second, new_id[t]);
      } else if (u_t >= 0 && in_gap[u_t]) {
        nb[k] = new_id[u_t];
      } else if (u_t < 0) {
        ++open_edges;
      } else {
        return false;  // the fill stopped at an edge that is no wall
      }
    }
    gap_neighbors.push_back(nb);
  }
  if (open_edges != hull_edges ||
      static_cast<int64_t>(wall_links.size()) != static_cast<int64_t>(walls.size()) - walls_on_hull)
    return false;
  for (size_t t = 0; t < mg; ++t)
    if (in_gap[t]) out.triangles.push_back({global(t, 0), global(t, 1), global(t, 2)});
  out.neighbors.insert(out.neighbors.end(), gap_neighbors.begin(), gap_neighbors.end());
  for (const auto& [use, gap] : wall_links) out.neighbors[use / 3][use % 3] = gap;
  return true;
}

// Removes the triangles of `u` with an edge on its boundary and recomputes the neighbours.
bool erode(size_t n, Triangulation& u) {
  size_t kept = 0;
  for (size_t t = 0; t < u.triangles.size(); ++t) {
    const auto& nb = u.neighbors[t];
    if (nb[0] >= 0 && nb[1] >= 0 && nb[2] >= 0) u.triangles[kept++] = u.triangles[t];
  }
  u.triangles.resize(kept);
  return triangle_neighbors(u.triangles, n, u.neighbors);
}

}  // namespace

Triangulation complete_triangulation(const std::vector<Vec2>& points, Triangulation partial,
                                     int32_t always_gap) {
  Triangulation out = std::move(partial);
  for (int erosions = 0;; ++erosions) {
    if (fill_gaps(points, always_gap, out)) return out;
    // Walls that cross or gaps that fold over: U's triangles along a straight boundary can be
    // flat, and those dropped when they turned over leave slits whose two sides cross by
    // rounding. Without the triangles next to every gap, the gaps are wide enough.
    if (erosions == kMaxErosions || !erode(points.size(), out)) return {};
  }
}

}  // namespace meshd
