// Gmsh MSH 2.2 ASCII, the legacy format that MFEM, OpenFOAM's gmshToFoam and many older tools
// read.
//
// Each element carries two tags, physical then elementary: lines get their group's physical tag
// (group + 2, as in mesh.h) and elementary tag group + 1 (the curve entity of the MSH 4.1
// writer); triangles get the domain's physical tag 1 and elementary tag 1. Node numbers are point
// index + 1; element numbers run over the lines first, then the triangles.
#pragma once

#include <ostream>

#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

// Writes mesh as MSH 2.2 ASCII with $PhysicalNames, $Nodes (z = 0) and $Elements (type 1 lines,
// type 2 triangles). Throws Error(kInternal) when the mesh's indices are out of range.
//
// mesh: #N points, #M triangles, #E boundary edges; triangles counter-clockwise.
// out: any output stream.
void write_msh22(const Mesh& mesh, std::ostream& out);
// The same for tetrahedra (4-node tetrahedra, type 4; 3-node boundary triangles, type 2).
void write_msh22(const TetMesh& mesh, std::ostream& out);

}  // namespace meshd
