// A structured test mesh: the rectangle [0, width] x [0, height] cut into nx by ny cells, each
// split into two counter-clockwise triangles, with the four sides as boundary groups.
#pragma once

#include "core/mesh/mesh.h"

namespace meshd::testing {

// Group indices of structured_square_mesh's boundary_names.
enum StructuredSide { kLeft = 0, kRight = 1, kBottom = 2, kTop = 3 };

// Returns a valid mesh with (nx + 1)(ny + 1) points, 2 nx ny triangles and 2 (nx + ny) boundary
// edges, named "left", "right", "bottom", "top". Point (i, j) has index j (nx + 1) + i.
// nx, ny: cells per side, >= 1. width, height: in the mesh's length unit.
inline Mesh structured_square_mesh(int nx, int ny, double width = 1.0, double height = 1.0) {
  Mesh mesh;
  auto index = [nx](int i, int j) { return static_cast<int32_t>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) mesh.points.push_back({width * i / nx, height * j / ny});
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  // Counter-clockwise around the rectangle, so the domain is on each edge's left.
  auto add = [&](int32_t a, int32_t b, StructuredSide side) {
    mesh.boundary_edges.push_back({a, b});
    mesh.boundary_tags.push_back(side);
  };
  for (int i = 0; i < nx; ++i) add(index(i, 0), index(i + 1, 0), kBottom);
  for (int j = 0; j < ny; ++j) add(index(nx, j), index(nx, j + 1), kRight);
  for (int i = nx; i > 0; --i) add(index(i, ny), index(i - 1, ny), kTop);
  for (int j = ny; j > 0; --j) add(index(0, j), index(0, j - 1), kLeft);
  mesh.boundary_names = {"left", "right", "bottom", "top"};
  return mesh;
}

}  // namespace meshd::testing
