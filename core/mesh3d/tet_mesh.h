// A tetrahedral mesh as arrays with integer indices (libigl style), the 3D twin of mesh.h.
//
// Invariants of a finished mesh (check_tet_validity verifies them): every tetrahedron (a, b, c, d)
// is positively oriented, orient3d = (b - a) . ((c - a) x (d - a)) = 6 V > 0, so that a, b, c turn
// counter-clockwise seen from d (0, e1, e2, e3 is positive); every face is shared by one
// tetrahedron (a boundary face) or by two that list it in opposite turns; every point is used;
// boundary_faces lists each boundary face once, turning counter-clockwise seen from outside (its
// right-hand-rule normal points out of the domain), and boundary_tags[i] indexes boundary_names.
// Physical groups in files are numbered as physical_groups.h says: the tetrahedra are the domain
// (1, dimension 3), boundary group i is i + 2 (dimension 2).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/vec3.h"
#include "core/mesh/physical_groups.h"

namespace meshd {

struct TetMesh {
  std::vector<Vec3> points;                            // #N by 3, request length unit
  std::vector<std::array<int32_t, 4>> tets;            // #M by 4, positively oriented
  std::vector<std::array<int32_t, 3>> boundary_faces;  // #F by 3, outward
  std::vector<int32_t> boundary_tags;                  // #F, index into boundary_names
  std::vector<std::string> boundary_names;             // one per boundary group
};

}  // namespace meshd
