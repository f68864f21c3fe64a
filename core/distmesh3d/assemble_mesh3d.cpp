#include "core/distmesh3d/assemble_mesh3d.h"

#include <utility>

#include "core/mesh3d/tet_boundary.h"

namespace meshd {

TetMesh assemble_mesh3d(const Domain3& domain, Relaxed3 relaxed) {
  TetMesh mesh;
  mesh.points = std::move(relaxed.points);
  mesh.tets = std::move(relaxed.tets);
  mesh.boundary_faces = tet_boundary_faces(mesh.tets);
  const bool grouped = domain.boundary_group && !domain.boundary_names.empty();
  mesh.boundary_names = grouped ? domain.boundary_names : std::vector<std::string>{"boundary"};
  mesh.boundary_tags.reserve(mesh.boundary_faces.size());
  for (const auto& f : mesh.boundary_faces) {
    const Vec3 centroid = (1.0 / 3.0) * (mesh.points[f[0]] + mesh.points[f[1]] + mesh.points[f[2]]);
    mesh.boundary_tags.push_back(grouped ? domain.boundary_group(centroid) : 0);
  }
  return mesh;
}

}  // namespace meshd
