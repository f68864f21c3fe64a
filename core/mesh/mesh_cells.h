// What the writers need to know of a mesh of either dimension, so that one writer per format
// serves triangles (mesh.h) and tetrahedra (tet_mesh.h) alike: the cells, the boundary facets
// with their groups, the points in space, and each cell's quality.
#pragma once

#include <cstdint>

#include "core/common/vec3.h"
#include "core/mesh/mesh.h"
#include "core/mesh/min_angle.cuh"
#include "core/mesh/radius_ratio.cuh"
#include "core/mesh3d/tet_mesh.h"
#include "core/mesh3d/tet_quality.cuh"

namespace meshd {

template <typename M>
struct MeshCells;

template <>
struct MeshCells<Mesh> {
  static constexpr int kDimension = 2;
  static constexpr int kMshCell = 2;       // 3-node triangle
  static constexpr int kMshFacet = 1;      // 2-node line
  static constexpr uint8_t kVtkCell = 5;   // VTK_TRIANGLE
  static constexpr uint8_t kVtkFacet = 3;  // VTK_LINE
  static constexpr const char* kAngleName = "min_angle";
  static const auto& cells(const Mesh& m) { return m.triangles; }
  static const auto& facets(const Mesh& m) { return m.boundary_edges; }
  static Vec3 point(const Mesh& m, size_t i) { return {m.points[i].x, m.points[i].y, 0.0}; }
  static double quality(const Mesh& m, const std::array<int32_t, 3>& t) {
    return radius_ratio(m.points[t[0]], m.points[t[1]], m.points[t[2]]);
  }
  // The smallest interior angle, degrees.
  static double angle(const Mesh& m, const std::array<int32_t, 3>& t) {
    return min_angle_deg(m.points[t[0]], m.points[t[1]], m.points[t[2]]);
  }
};

template <>
struct MeshCells<TetMesh> {
  static constexpr int kDimension = 3;
  static constexpr int kMshCell = 4;       // 4-node tetrahedron
  static constexpr int kMshFacet = 2;      // 3-node triangle
  static constexpr uint8_t kVtkCell = 10;  // VTK_TETRA
  static constexpr uint8_t kVtkFacet = 5;  // VTK_TRIANGLE
  static constexpr const char* kAngleName = "min_dihedral";
  static const auto& cells(const TetMesh& m) { return m.tets; }
  static const auto& facets(const TetMesh& m) { return m.boundary_faces; }
  static Vec3 point(const TetMesh& m, size_t i) { return m.points[i]; }
  static double quality(const TetMesh& m, const std::array<int32_t, 4>& t) {
    return oriented_tet_radius_ratio(m.points[t[0]], m.points[t[1]], m.points[t[2]],
                                     m.points[t[3]]);
  }
  // The smallest dihedral angle, degrees.
  static double angle(const TetMesh& m, const std::array<int32_t, 4>& t) {
    double lo = 0.0, hi = 0.0;
    tet_dihedral_range(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]], lo, hi);
    return lo;
  }
};

}  // namespace meshd
