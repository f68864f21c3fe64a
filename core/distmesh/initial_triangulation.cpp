#include "core/distmesh/initial_triangulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "core/delaunay/complete_triangulation.h"
#include "core/distmesh/lattice_triangles.cuh"

namespace meshd {
namespace {

bool all_kept(const LatticeTriangle& t, const std::vector<uint8_t>& kept) {
  return kept[t.v[0]] && kept[t.v[1]] && kept[t.v[2]];
}

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
        u.triangles.push_back({index[t.v[0]], index[t.v[1]], index[t.v[2]]});
      }
    }
  }
  for (int64_t r = 0; r + 1 < grid.ny; ++r) {
    for (int64_t i = 0; i + 1 < grid.nx; ++i) {
      for (int s = 0; s < 2; ++s) {
        if (in_u[lattice_id(grid, r, i, s)] < 0) continue;
        std::array<int32_t, 3> nb{-1, -1, -1};
        for (int k = 0; k < 3; ++k) {
          const int64_t across = lattice_neighbor(grid, r, i, s, k);
          if (across >= 0) nb[k] = in_u[across];
        }
        u.neighbors.push_back(nb);
      }
    }
  }
  return complete_triangulation(points, std::move(u), nfix);
}

}  // namespace meshd
