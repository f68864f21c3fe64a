// VTK XML UnstructuredGrid (.vtu) for ParaView, VisIt and meshio.
//
// Cells: the #M triangles first (VTK_TRIANGLE 5; cell i is triangle i), then the #E boundary
// edges as lines (VTK_LINE 3; cell #M + i is boundary edge i). Lines are kept so that the
// boundary groups can be seen and selected (threshold on "physical").
// Cell data:
//   "quality"    Float64, radius ratio in [0, 1]; NaN for lines,
//   "min_angle"  Float64, smallest interior angle in degrees; NaN for lines,
//   "physical"   Int32, kDomainPhysicalTag for triangles, boundary_physical_tag(group) for lines.
// NaN rather than a sentinel such as -1 for lines: VTK's range computation skips NaN, so colour
// maps span the triangles' values only, and no reader mistakes a line for a bad triangle.
// Field data: one Int32 array per physical group, named after it, holding {tag, dimension}
// ("domain" = {1, 2}, each boundary group {group + 2, 1}); meshio reads these as field_data in
// the same form as the physical names of a .msh file.
// Points have three components with z = 0.
#pragma once

#include <ostream>

#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

// Writes mesh as a .vtu file with inline binary arrays (format="binary": base64 of a UInt64 byte
// count followed by the raw values in this machine's byte order, encoded as one stream, as VTK
// itself writes them). Throws Error(kInternal) when the mesh's indices are out of range.
//
// mesh: #N points, #M triangles, #E boundary edges.
// out: any output stream.
void write_vtu(const Mesh& mesh, std::ostream& out);
// The same for tetrahedra: the #M tetrahedra (VTK_TETRA 10) first, then the #F boundary faces
// (VTK_TRIANGLE 5); "min_dihedral" (degrees) in place of "min_angle"; field data {tag, dimension}
// with the domain of dimension 3 and the groups of dimension 2.
void write_vtu(const TetMesh& mesh, std::ostream& out);

}  // namespace meshd
