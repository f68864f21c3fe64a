// A tetrahedral mesh as arrays with integer indices (libigl style), the 3D twin of mesh.h.
//
// Invariants of a finished mesh: every tetrahedron is positively oriented,
// (b - a) . ((c - a) x (d - a)) > 0; every face is shared by one tetrahedron (a boundary face) or
// two; every point is used; boundary_faces lists each boundary face once, turning
// counter-clockwise seen from outside (its normal by the right-hand rule points out of the
// domain), and boundary_tags[i] indexes boundary_names.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

struct TetMesh {
  std::vector<Vec3> points;                            // #N by 3, request length unit
  std::vector<std::array<int32_t, 4>> tets;            // #M by 4, positively oriented
  std::vector<std::array<int32_t, 3>> boundary_faces;  // #F by 3, outward
  std::vector<int32_t> boundary_tags;                  // #F, index into boundary_names
  std::vector<std::string> boundary_names;             // one per boundary group
};

}  // namespace meshd
