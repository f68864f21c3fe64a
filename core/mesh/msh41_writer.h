// Gmsh MSH 4.1 (Gmsh 4.x's native format), ASCII or binary.
//
// Layout: one entity of the mesh's dimension (tag 1: a surface for triangles, a volume for
// tetrahedra) in the domain's physical group, one entity a dimension lower per boundary group
// (tag group + 1) in that group's physical group (numbers as in mesh.h), all nodes in the
// domain's entity, the boundary facets (2-node lines, 3-node triangles) per group's entity and
// the cells (3-node triangles, 4-node tetrahedra) in the domain's. Node tags are point index + 1;
// element tags run over the facets first, then the cells (cell i has tag #E + i + 1).
#pragma once

#include <ostream>

#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

enum class MshEncoding { kAscii, kBinary };

// Writes mesh as MSH 4.1. Binary follows the spec's binary mode: sizes and tags as 8-byte
// size_t, entity and type numbers as 4-byte int, coordinates as double, all in this machine's
// byte order, announced by the int 1 after the header line. Throws Error(kInternal) when the
// mesh's indices are out of range (check_indices).
//
// mesh: #N points, #M triangles, #E boundary edges; triangles counter-clockwise.
// out: a stream opened in binary mode (text-mode newline translation would corrupt binary
//      files).
void write_msh41(const Mesh& mesh, std::ostream& out, MshEncoding encoding = MshEncoding::kAscii);
// The same for tetrahedra: mesh: #N points, #M tetrahedra, #F boundary faces.
void write_msh41(const TetMesh& mesh, std::ostream& out,
                 MshEncoding encoding = MshEncoding::kAscii);

}  // namespace meshd
