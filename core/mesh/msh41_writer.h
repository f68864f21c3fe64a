// Gmsh MSH 4.1 (Gmsh 4.x's native format), ASCII or binary.
//
// Layout: one surface entity (tag 1) in the domain's physical group, one curve entity per
// boundary group (tag group + 1) in that group's physical group (numbers as in mesh.h), all nodes
// in the surface entity, 2-node lines per curve entity and 3-node triangles in the surface.
// Node tags are point index + 1; element tags run over the lines first, then the triangles
// (triangle i has tag #E + i + 1).
#pragma once

#include <ostream>

#include "core/mesh/mesh.h"

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

}  // namespace meshd
