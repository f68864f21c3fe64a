// Choosing a mesh file format by name or extension, and writing a mesh file safely.
#pragma once

#include <ostream>
#include <string>

#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

enum class MeshFormat {
  kMsh41,        // Gmsh MSH 4.1 ASCII, ".msh", name "msh41"
  kMsh41Binary,  // Gmsh MSH 4.1 binary, name "msh41-binary" (no extension of its own)
  kMsh22,        // Gmsh MSH 2.2 ASCII, ".msh22", name "msh22"
  kVtu,          // VTK XML unstructured grid, ".vtu", name "vtu"
  kSvg,          // SVG picture, ".svg", name "svg"
};

// The format's name as parse_format_name accepts it ("msh41", "msh41-binary", ...).
const char* format_name(MeshFormat format);

// The format for a file name's extension (ASCII case ignored): .msh, .msh22, .vtu, .svg.
// Throws Error(kInvalidArgument) naming field and the allowed extensions otherwise.
MeshFormat format_from_path(const std::string& path, const std::string& field = "output");

// The format for a name: "msh41", "msh41-binary", "msh22", "vtu" or "svg" (exact, lower case).
// Throws Error(kInvalidArgument) naming field and the allowed names otherwise.
MeshFormat parse_format_name(const std::string& name, const std::string& field = "format");

// Writes mesh to out in format, with the writer's defaults. out should be in binary mode.
void write_mesh(const Mesh& mesh, std::ostream& out, MeshFormat format);

// Writes mesh to the file at path, first to a temporary file in the same directory that is then
// renamed over path, so that readers never see a half-written file and a failed write leaves any
// old file in place. Throws Error with field "output": kInvalidArgument when the file cannot be
// created or renamed (no such directory, no permission), kResourceExhausted when writing fails
// (disk full); the writers' Error(kInternal) for a mesh with bad indices passes through. The
// temporary file is removed on every failure.
void write_mesh_file(const Mesh& mesh, const std::string& path, MeshFormat format);

// Writes a tetrahedral mesh to out in format: the tetrahedra in the domain's physical group
// (dimension 3), the boundary faces as triangles in one group per boundary name (dimension 2).
// kSvg is a picture of its surface (svg_surface3d.h). Bad indices get the writers'
// Error(kInternal). out should be in binary mode.
void write_mesh(const TetMesh& mesh, std::ostream& out, MeshFormat format);

// Writes a tetrahedral mesh to the file at path as write_mesh_file does (a temporary file renamed
// over path; the same errors, with no file left behind).
void write_mesh_file(const TetMesh& mesh, const std::string& path, MeshFormat format);

}  // namespace meshd
