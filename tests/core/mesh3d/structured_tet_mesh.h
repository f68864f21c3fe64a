// A structured tetrahedral mesh of the unit cube for tests: n^3 cells, each cut into six
// tetrahedra around its diagonal from (0,0,0) to (1,1,1) (Kuhn's subdivision, conforming across
// cells), with the six faces as boundary groups x0, x1, y0, y1, z0, z1.
#pragma once

#include <array>
#include <utility>

#include "core/mesh3d/tet_boundary.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd::testing {

inline TetMesh structured_cube_mesh(int n) {
  TetMesh mesh;
  const auto index = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.points.push_back(
            {static_cast<double>(i) / n, static_cast<double>(j) / n, static_cast<double>(k) / n});
  // The six monotone paths from corner 0 to corner 7 of a cell (corner c at offsets c&1,
  // c>>1&1, c>>2&1), one tetrahedron each.
  const int paths[6][2] = {{1, 3}, {2, 3}, {1, 5}, {4, 5}, {2, 6}, {4, 6}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto corner = [&](int c) {
          return static_cast<int32_t>(index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)));
        };
        for (const auto& p : paths) {
          std::array<int32_t, 4> t{corner(0), corner(p[0]), corner(p[1]), corner(7)};
          const Vec3 a = mesh.points[t[0]];
          if (dot(mesh.points[t[1]] - a, cross(mesh.points[t[2]] - a, mesh.points[t[3]] - a)) < 0)
            std::swap(t[1], t[2]);
          mesh.tets.push_back(t);
        }
      }
  mesh.boundary_names = {"x0", "x1", "y0", "y1", "z0", "z1"};
  mesh.boundary_faces = tet_boundary_faces(mesh.tets);
  for (const auto& f : mesh.boundary_faces) {
    const Vec3 c = (1.0 / 3.0) * (mesh.points[f[0]] + mesh.points[f[1]] + mesh.points[f[2]]);
    const double eps = 1e-9;
    mesh.boundary_tags.push_back(c.x < eps       ? 0
                                 : c.x > 1 - eps ? 1
                                 : c.y < eps     ? 2
                                 : c.y > 1 - eps ? 3
                                 : c.z < eps     ? 4
                                                 : 5);
  }
  return mesh;
}

}  // namespace meshd::testing
