// How far a tetrahedral mesh's surface nodes lie from the domain's boundary: the check behind
// "boundary nodes on the boundary" in the 3D quality report.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

struct SurfaceOffset3 {
  double max = 0.0;     // the largest |distance| of a surface node, the request's length unit
  int64_t beyond = 0;   // surface nodes with |distance| over the tolerance given
  int64_t surface = 0;  // nodes of the mesh's boundary faces
};

// Over the nodes of `boundary_faces` (#F by 3 indices in [0, #N), not checked). points: #N by 3;
// tolerance >= 0 in the request's length unit.
SurfaceOffset3 surface_offset3d(const Domain3& domain, const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 3>>& boundary_faces,
                                double tolerance);
// The same over the faces that one tetrahedron alone uses (tet_boundary_faces), for arrays not
// yet assembled into a TetMesh.
SurfaceOffset3 surface_offset3d(const Domain3& domain, const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 4>>& tets, double tolerance);

}  // namespace meshd
