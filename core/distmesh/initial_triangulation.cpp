#include "core/distmesh/initial_triangulation.h"

#include <array>
#include <cmath>
#include <set>
#include <unordered_set>

#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/triangle_neighbors.h"

namespace meshd {
namespace {

// Lattice triangle s (0 or 1) of column i between rows r and r + 1, as grid indices, counter-
// clockwise. Even rows are not shifted, odd rows are shifted right by half a column.
std::array<int64_t, 3> lattice_triangle(const InitialGrid& g, int64_t r, int64_t i, int s) {
  const int64_t a = r * g.nx + i, b = (r + 1) * g.nx + i;  // a: row r, b: row r + 1
  if ((r & 1) == 0) {
    return s == 0 ? std::array<int64_t, 3>{a, a + 1, b} : std::array<int64_t, 3>{a + 1, b + 1, b};
  }
  return s == 0 ? std::array<int64_t, 3>{a, b + 1, b} : std::array<int64_t, 3>{a, a + 1, b + 1};
}

bool all_kept(const std::array<int64_t, 3>& t, const std::vector<uint8_t>& kept) {
  return kept[t[0]] && kept[t[1]] && kept[t[2]];
}

int64_t lattice_id(const InitialGrid& g, int64_t r, int64_t i, int s) {
  return (r * (g.nx - 1) + i) * 2 + s;
}

// Calls f(r, i, s) for each lattice triangle whose closure holds q (a few cells around it).
template <typename F>
void for_lattice_triangles_at(const InitialGrid& g, Vec2 q, F f) {
  const double row = std::floor((q.y - g.origin.y) / g.dy);
  const double col = std::floor((q.x - g.origin.x) / g.dx);
  if (!(row > -2.0 && row < static_cast<double>(g.ny) + 1.0 && col > -3.0 &&
        col < static_cast<double>(g.nx) + 2.0))
    return;
  const auto r0 = static_cast<int64_t>(row), i0 = static_cast<int64_t>(col);
  for (int64_t r = r0 - 1; r <= r0 + 1; ++r) {
    if (r < 0 || r > g.ny - 2) continue;
    for (int64_t i = i0 - 2; i <= i0 + 1; ++i) {
      if (i < 0 || i > g.nx - 2) continue;
      for (int s = 0; s < 2; ++s) {
        const auto t = lattice_triangle(g, r, i, s);
        const Vec2 a = initial_grid_point(g, t[0]), b = initial_grid_point(g, t[1]),
                   c = initial_grid_point(g, t[2]);
        if (cross(b - a, q - a) >= 0.0 && cross(c - b, q - b) >= 0.0 && cross(a - c, q - c) >= 0.0)
          f(r, i, s);
      }
    }
  }
}

// The lattice triangles in U: three kept corners and no fixed point in them (a fixed point can
// sit near a triangle's centre, farther than step 2's exclusion radius from its corners).
struct LatticeUnion {
  const InitialGrid& grid;
  const std::vector<uint8_t>& kept;
  std::set<int64_t> blocked;

  bool contains(int64_t r, int64_t i, int s) const {
    return all_kept(lattice_triangle(grid, r, i, s), kept) &&
           (blocked.empty() || blocked.count(lattice_id(grid, r, i, s)) == 0);
  }
};

}  // namespace

Triangulation initial_triangulation(const InitialGrid& grid, const std::vector<uint8_t>& kept,
                                    const std::vector<Vec2>& fixed) {
  const auto nfix = static_cast<int32_t>(fixed.size());
  const int64_t total = grid.nx * grid.ny;
  std::vector<int32_t> index(total, -1);
  std::vector<Vec2> points(fixed.begin(), fixed.end());
  for (int64_t k = 0; k < total; ++k) {
    if (!kept[k]) continue;
    index[k] = static_cast<int32_t>(points.size());
    points.push_back(initial_grid_point(grid, k));
  }
  const size_t n = points.size();

  LatticeUnion u{grid, kept, {}};
  for (const Vec2 f : fixed) {
    for_lattice_triangles_at(grid, f, [&](int64_t r, int64_t i, int s) {
      u.blocked.insert(lattice_id(grid, r, i, s));
    });
  }
  Triangulation out;
  for (int64_t r = 0; r + 1 < grid.ny; ++r) {
    for (int64_t i = 0; i + 1 < grid.nx; ++i) {
      for (int s = 0; s < 2; ++s) {
        if (!u.contains(r, i, s)) continue;
        const auto t = lattice_triangle(grid, r, i, s);
        out.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
      }
    }
  }
  if (!triangle_neighbors(out.triangles, n, out.neighbors)) return {};

  // The points that bound a gap: on U's boundary, in no lattice triangle, or fixed. U's
  // boundary edges, directed with U on their left.
  std::vector<char> in_u(n, 0), on_gap(n, 0);
  std::unordered_set<uint64_t> walls;
  auto key = [](int32_t from, int32_t to) {
    return (uint64_t{static_cast<uint32_t>(from)} << 32) | static_cast<uint32_t>(to);
  };
  for (size_t t = 0; t < out.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      in_u[out.triangles[t][k]] = 1;
      if (out.neighbors[t][k] >= 0) continue;
      const int32_t from = out.triangles[t][(k + 1) % 3], to = out.triangles[t][(k + 2) % 3];
      on_gap[from] = on_gap[to] = 1;
      walls.insert(key(from, to));
    }
  }
  std::vector<int32_t> gap_index;
  std::vector<Vec2> gap_points;
  for (size_t v = 0; v < n; ++v) {
    if (v < static_cast<size_t>(nfix) || !in_u[v] || on_gap[v]) {
      gap_index.push_back(static_cast<int32_t>(v));
      gap_points.push_back(points[v]);
    }
  }
  const Triangulation gaps = delaunay_triangulate(gap_points);

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
  if (walls_seen != 2 * static_cast<int64_t>(walls.size()) - walls_on_hull) return {};
  for (size_t t = 0; t < mg; ++t) {
    if (!in_gap[t]) continue;
    const auto& g = gaps.triangles[t];
    if (orientation_sign(gap_points[g[0]], gap_points[g[1]], gap_points[g[2]]) <= 0) return {};
    out.triangles.push_back({gap_index[g[0]], gap_index[g[1]], gap_index[g[2]]});
  }

  // A triangulation of N points with H on the hull has 2 N - 2 - H triangles.
  if (static_cast<int64_t>(out.triangles.size()) != 2 * static_cast<int64_t>(n) - 2 - hull_edges)
    return {};
  if (!triangle_neighbors(out.triangles, n, out.neighbors)) return {};
  int64_t open_edges = 0;
  for (const auto& nb : out.neighbors) open_edges += (nb[0] < 0) + (nb[1] < 0) + (nb[2] < 0);
  if (open_edges != hull_edges) return {};
  return out;
}

}  // namespace meshd
