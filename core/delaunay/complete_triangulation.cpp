#include "core/delaunay/complete_triangulation.h"

#include <unordered_map>
#include <utility>

#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/triangle_neighbors.h"

namespace meshd {
namespace {

uint64_t wall_key(int32_t from, int32_t to) {
  return (uint64_t{static_cast<uint32_t>(from)} << 32) | static_cast<uint32_t>(to);
}

// gap_boundary's work on the host.
GapBoundary find_gap_boundary(const std::vector<Vec2>& points, int32_t always_gap,
                              const Triangulation& u) {
  const size_t n = points.size();
  GapBoundary b;
  std::vector<char> in_u(n, 0), on_gap(n, 0);
  for (size_t t = 0; t < u.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      in_u[u.triangles[t][k]] = 1;
      if (u.neighbors[t][k] >= 0) continue;
      const int32_t from = u.triangles[t][(k + 1) % 3], to = u.triangles[t][(k + 2) % 3];
      on_gap[from] = on_gap[to] = 1;
      b.walls.push_back({from, to});
      b.wall_uses.push_back(static_cast<int64_t>(3 * t + k));
    }
  }
  for (size_t v = 0; v < n; ++v) {
    if (v < static_cast<size_t>(always_gap) || !in_u[v] || on_gap[v]) {
      b.points.push_back(static_cast<int32_t>(v));
      b.positions.push_back(points[v]);
    }
  }
  return b;
}

// Appends `fill` to `out`, U's triangles and neighbours.
void append_fill(const GapFill& fill, Triangulation& out) {
  out.triangles.insert(out.triangles.end(), fill.triangles.begin(), fill.triangles.end());
  out.neighbors.insert(out.neighbors.end(), fill.neighbors.begin(), fill.neighbors.end());
  for (const auto& [use, gap] : fill.wall_links) out.neighbors[use / 3][use % 3] = gap;
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

bool fill_gaps(const GapBoundary& boundary, int64_t n, int64_t u_count, GapFill& fill) {
  fill = {};
  // Each wall's use in U, by (from, to); local index of each gap point.
  std::unordered_map<uint64_t, int64_t> walls;
  walls.reserve(boundary.walls.size());
  for (size_t w = 0; w < boundary.walls.size(); ++w)
    walls.emplace(wall_key(boundary.walls[w][0], boundary.walls[w][1]), boundary.wall_uses[w]);
  std::unordered_map<int32_t, int32_t> local;
  local.reserve(boundary.points.size());
  for (size_t i = 0; i < boundary.points.size(); ++i)
    local.emplace(boundary.points[i], static_cast<int32_t>(i));
  const std::vector<int32_t>& gap_index = boundary.points;
  const std::vector<Vec2>& gap_points = boundary.positions;
  // The walls as constraints: a Delaunay edge of U need not be an edge of CGAL's Delaunay
  // triangulation of the gaps' points when those are co-circular (a hole's boundary nodes all
  // lie on its circle, and a dropped sliver there leaves walls that are chords of it).
  std::vector<std::array<int32_t, 2>> constraints;
  constraints.reserve(boundary.walls.size());
  for (const auto& w : boundary.walls) {
    const auto from = local.find(w[0]), to = local.find(w[1]);
    if (from == local.end() || to == local.end()) return false;  // a wall end not listed
    constraints.push_back({from->second, to->second});
  }
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
    return walls.count(wall_key(from, to)) + walls.count(wall_key(to, from)) > 0;
  };
  for (size_t t = 0; t < mg; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t from = global(t, (k + 1) % 3), to = global(t, (k + 2) % 3);
      const bool u_left = walls.count(wall_key(from, to)) > 0;
      const bool u_right = walls.count(wall_key(to, from)) > 0;
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
  int64_t next_id = u_count;
  for (size_t t = 0; t < mg; ++t) {
    if (!in_gap[t]) continue;
    const auto& g = gaps.triangles[t];
    if (orientation_sign(gap_points[g[0]], gap_points[g[1]], gap_points[g[2]]) <= 0) return false;
    new_id[t] = static_cast<int32_t>(next_id++);
  }
  // A triangulation of N points with H on the hull has 2 N - 2 - H triangles.
  if (next_id != 2 * n - 2 - hull_edges) return false;

  // The links, without a pass over all triangles. A gap triangle's edge borders another gap
  // triangle, or is a wall with U on the other side, or lies on the hull. With every triangle
  // counter-clockwise, U linked consistently and the open edges exactly the hull's, the
  // triangles cover the hull once: they form a triangulation.
  std::vector<std::array<int32_t, 3>>& gap_neighbors = fill.neighbors;
  gap_neighbors.reserve(static_cast<size_t>(next_id - u_count));
  std::vector<std::pair<int64_t, int32_t>>& wall_links = fill.wall_links;
  int64_t open_edges = walls_on_hull;
  for (size_t t = 0; t < mg; ++t) {
    if (!in_gap[t]) continue;
    std::array<int32_t, 3> nb{-1, -1, -1};
    for (int k = 0; k < 3; ++k) {
      const int32_t from = global(t, (k + 1) % 3), to = global(t, (k + 2) % 3);
      const int32_t u_t = gaps.neighbors[t][k];
      if (walls.count(wall_key(from, to)) > 0) return false;  // a gap triangle on U's side
      const auto wall = walls.find(wall_key(to, from));
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
    if (in_gap[t]) fill.triangles.push_back({global(t, 0), global(t, 1), global(t, 2)});
  return true;
}

Triangulation complete_triangulation(const std::vector<Vec2>& points, Triangulation partial,
                                     int32_t always_gap) {
  Triangulation out = std::move(partial);
  const auto n = static_cast<int64_t>(points.size());
  for (int erosions = 0;; ++erosions) {
    GapFill fill;
    if (fill_gaps(find_gap_boundary(points, always_gap, out), n,
                  static_cast<int64_t>(out.triangles.size()), fill)) {
      append_fill(fill, out);
      return out;
    }
    // Walls that cross or gaps that fold over: U's triangles along a straight boundary can be
    // flat, and those dropped when they turned over leave slits whose two sides cross by
    // rounding. Without the triangles next to every gap, the gaps are wide enough.
    if (erosions == kMaxCompletionErosions || !erode(points.size(), out)) return {};
  }
}

}  // namespace meshd
