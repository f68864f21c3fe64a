// The triangles of the initial points' equilateral lattice (initial_points.cuh), numbered and
// linked without matching edges: shared by the host's initial triangulation
// (initial_triangulation.h) and the GPU engine's (kernels/lattice_triangulation.h).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/distmesh/initial_points.cuh"

namespace meshd {

struct LatticeTriangle {
  int64_t v[3];  // grid indices, counter-clockwise
};

// Lattice triangle s (0 or 1) of column i between rows r and r + 1. Even rows are not shifted,
// odd rows are shifted right by half a column.
MESHD_HD inline LatticeTriangle lattice_triangle(const InitialGrid& g, int64_t r, int64_t i,
                                                 int s) {
  const int64_t a = r * g.nx + i, b = (r + 1) * g.nx + i;  // a: row r, b: row r + 1
  if ((r & 1) == 0)
    return s == 0 ? LatticeTriangle{{a, a + 1, b}} : LatticeTriangle{{a + 1, b + 1, b}};
  return s == 0 ? LatticeTriangle{{a, b + 1, b}} : LatticeTriangle{{a, a + 1, b + 1}};
}

// Lattice triangles are numbered row by row, column by column, s last.
MESHD_HD inline int64_t lattice_id(const InitialGrid& g, int64_t r, int64_t i, int s) {
  return (r * (g.nx - 1) + i) * 2 + s;
}
MESHD_HD inline int64_t lattice_triangle_count(const InitialGrid& g) {
  return g.nx > 1 && g.ny > 1 ? 2 * (g.nx - 1) * (g.ny - 1) : 0;
}

// The id of the lattice triangle across the edge opposite corner k of triangle (r, i, s), or -1
// outside the lattice. The lattice is the same in every cell, so its neighbours are known: across
// that edge lies triangle (r + dr, i + di, s') for {dr, di, s'} = table[r & 1][s][k].
MESHD_HD inline int64_t lattice_neighbor(const InitialGrid& g, int64_t r, int64_t i, int s, int k) {
  constexpr int table[2][2][3][3] = {
      {{{0, 0, 1}, {0, -1, 1}, {-1, 0, 0}}, {{1, 0, 1}, {0, 0, 0}, {0, 1, 0}}},   // even rows
      {{{1, 0, 0}, {0, -1, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 0, 0}, {-1, 0, 1}}}};  // odd rows
  const int* d = table[r & 1][s][k];
  const int64_t nr = r + d[0], ni = i + d[1];
  if (nr < 0 || nr + 1 >= g.ny || ni < 0 || ni + 1 >= g.nx) return -1;
  return lattice_id(g, nr, ni, d[2]);
}

// Calls f(r, i, s) for each lattice triangle whose closure holds q (a few cells around it).
template <typename F>
MESHD_HD void for_lattice_triangles_at(const InitialGrid& g, Vec2 q, F f) {
  const double row = floor((q.y - g.origin.y) / g.dy);
  const double col = floor((q.x - g.origin.x) / g.dx);
  if (!(row > -2.0 && row < static_cast<double>(g.ny) + 1.0 && col > -3.0 &&
        col < static_cast<double>(g.nx) + 2.0))
    return;
  const auto r0 = static_cast<int64_t>(row), i0 = static_cast<int64_t>(col);
  for (int64_t r = r0 - 1; r <= r0 + 1; ++r) {
    if (r < 0 || r > g.ny - 2) continue;
    for (int64_t i = i0 - 2; i <= i0 + 1; ++i) {
      if (i < 0 || i > g.nx - 2) continue;
      for (int s = 0; s < 2; ++s) {
        const LatticeTriangle t = lattice_triangle(g, r, i, s);
        const Vec2 a = initial_grid_point(g, t.v[0]), b = initial_grid_point(g, t.v[1]),
                   c = initial_grid_point(g, t.v[2]);
        if (cross(b - a, q - a) >= 0.0 && cross(c - b, q - b) >= 0.0 && cross(a - c, q - c) >= 0.0)
          f(r, i, s);
      }
    }
  }
}

}  // namespace meshd
