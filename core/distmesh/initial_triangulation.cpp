#include "core/distmesh/initial_triangulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/delaunay/complete_triangulation.h"

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

// Lattice triangle s of column i between rows r and r + 1 borders, across the edge opposite its
// corner k, triangle (r + dr, i + di, s') of kNeighbor[r & 1][s][k] = {dr, di, s'}: the lattice
// is the same in every cell, so its neighbours are known without matching edges.
constexpr int kNeighbor[2][2][3][3] = {
    {{{0, 0, 1}, {0, -1, 1}, {-1, 0, 0}}, {{1, 0, 1}, {0, 0, 0}, {0, 1, 0}}},   // even rows
    {{{1, 0, 0}, {0, -1, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 0, 0}, {-1, 0, 1}}}};  // odd rows

}  // namespace

Triangulation initial_triangulation(const InitialGrid& grid, const std::vector<uint8_t>& kept,
                                    const std::vector<Vec2>& fixed) {
  const auto nfix = static_cast<int32_t>(fixed.size());
  const int64_t total = grid.nx * grid.ny;
  std::vector<int32_t> index(total, -1);
  std::vector<Vec2> points;
  points.reserve(fixed.size() + static_cast<size_t>(std::count(kept.begin(), kept.end(), 1)));
  points.assign(fixed.begin(), fixed.end());
  for (int64_t k = 0; k < total; ++k) {
    if (!kept[k]) continue;
    index[k] = static_cast<int32_t>(points.size());
    points.push_back(initial_grid_point(grid, k));
  }
  // U: the lattice triangles with three kept corners and no fixed point in them (a fixed point
  // can sit near a triangle's centre, farther than step 2's exclusion radius from its corners).
  // in_u[lattice id]: the triangle's index in U, -1 when not in U.
  constexpr int32_t kBlocked = -2;
  const int64_t cells = std::max<int64_t>(grid.ny - 1, 0) * std::max<int64_t>(grid.nx - 1, 0);
  std::vector<int32_t> in_u(2 * cells, -1);
  for (const Vec2 f : fixed) {
    for_lattice_triangles_at(
        grid, f, [&](int64_t r, int64_t i, int s) { in_u[lattice_id(grid, r, i, s)] = kBlocked; });
  }
  // A triangulation of N points has fewer than 2 N triangles: room for all of them spares the
  // completion's appends a copy of U (pages never written cost nothing).
  Triangulation u;
  u.triangles.reserve(2 * points.size());
  u.neighbors.reserve(2 * points.size());
  for (int64_t r = 0; r + 1 < grid.ny; ++r) {
    for (int64_t i = 0; i + 1 < grid.nx; ++i) {
      for (int s = 0; s < 2; ++s) {
        int32_t& id = in_u[lattice_id(grid, r, i, s)];
        const auto t = lattice_triangle(grid, r, i, s);
        if (id == kBlocked || !all_kept(t, kept)) {
          id = -1;
          continue;
        }
        id = static_cast<int32_t>(u.triangles.size());
        u.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
      }
    }
  }
  for (int64_t r = 0; r + 1 < grid.ny; ++r) {
    for (int64_t i = 0; i + 1 < grid.nx; ++i) {
      for (int s = 0; s < 2; ++s) {
        if (in_u[lattice_id(grid, r, i, s)] < 0) continue;
        std::array<int32_t, 3> nb{-1, -1, -1};
        for (int k = 0; k < 3; ++k) {
          const int* d = kNeighbor[r & 1][s][k];
          const int64_t nr = r + d[0], ni = i + d[1];
          if (nr >= 0 && nr + 1 < grid.ny && ni >= 0 && ni + 1 < grid.nx)
            nb[k] = in_u[lattice_id(grid, nr, ni, d[2])];
        }
        u.neighbors.push_back(nb);
      }
    }
  }
  return complete_triangulation(points, std::move(u), nfix);
}

}  // namespace meshd
