// A triangle mesh as arrays with integer indices (libigl style).
//
// Invariants of a finished mesh (check_validity verifies them): triangles are counter-clockwise
// with positive area; every edge is shared by one triangle (a boundary edge) or two with
// opposite orientation; every point is used; boundary_edges lists each boundary edge once,
// oriented with the domain on its left, and boundary_tags[i] indexes boundary_names.
// Physical groups in files are numbered as physical_groups.h says: the triangles are the domain
// (1, dimension 2), boundary group i is i + 2 (dimension 1).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/vec2.h"
#include "core/mesh/physical_groups.h"

namespace meshd {

struct Mesh {
  std::vector<Vec2> points;                            // #N by 2, request length unit
  std::vector<std::array<int32_t, 3>> triangles;       // #M by 3, counter-clockwise
  std::vector<std::array<int32_t, 2>> boundary_edges;  // #E by 2, domain on the left
  std::vector<int32_t> boundary_tags;                  // #E, index into boundary_names
  std::vector<std::string> boundary_names;             // one per boundary group
};

}  // namespace meshd
