// Checks of a tetrahedral mesh's invariants (tet_mesh.h), as validity.h does for triangles.
#pragma once

#include <string>
#include <vector>

#include "core/mesh3d/tet_mesh.h"

namespace meshd {

struct TetValidityReport {
  std::vector<std::string> problems;  // empty when valid; at most a few per kind, then a count
  bool valid() const { return problems.empty(); }
};

// Every invariant of tet_mesh.h: indices in range, positive volumes, every face shared by one
// or two tetrahedra, boundary_faces exactly the faces used once and turned outward, tags in
// range, every point used.
TetValidityReport check_tet_validity(const TetMesh& mesh);

// Only what a writer needs to read the mesh safely: indices in [0, #N), one tag per boundary
// face, tags in [0, #boundary_names). Throws Error(kInternal, field "mesh") naming the first
// offender.
void check_indices(const TetMesh& mesh);

}  // namespace meshd
