// The finished 3D mesh: the relaxed tetrahedra with their boundary faces, each in the boundary
// group of the primitive it lies on.
#pragma once

#include "core/distmesh3d/distmesh3d.h"
#include "core/distmesh3d/domain3d.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

// The boundary faces of `relaxed` (tet_boundary.h), tagged with domain.boundary_group at their
// centroid (one group "boundary" where the domain has none).
TetMesh assemble_mesh3d(const Domain3& domain, Relaxed3 relaxed);

}  // namespace meshd
