// Writes a structured 20 x 20 square mesh in every format, for check_mesh_files.py to read back
// with meshio and gmsh. Usage: write_sample_meshes OUTPUT_DIR (created if missing)
// Files: square.msh (MSH 4.1 ASCII), square_binary.msh (MSH 4.1 binary), square.msh22,
// square.vtu, square.svg. Expected: 441 nodes, 800 triangles, 80 boundary edges, groups
// left,right,bottom,top. And a structured 4 x 4 x 4 cube of tetrahedra (check_tet_files.py):
// cube.msh, cube_binary.msh, cube.msh22, cube.vtu; 125 nodes, 384 tetrahedra, 192 boundary
// triangles, groups x0,x1,y0,y1,z0,z1, volume 1.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "core/mesh/mesh_file.h"
#include "core/mesh/validity.h"
#include "core/mesh3d/tet_validity.h"
#include "tests/core/mesh/structured_mesh.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace {

struct Output {
  const char* file;
  meshd::MeshFormat format;
};

// Writes mesh into dir in each of outputs; false (with a message) when one fails.
template <typename M>
bool write_all(const M& mesh, const std::string& dir, const std::vector<Output>& outputs) {
  try {
    std::filesystem::create_directories(dir);
    for (const Output& output : outputs) {
      const std::string path = dir + "/" + output.file;
      meshd::write_mesh_file(mesh, path, output.format);
      std::printf("wrote %s (%s)\n", path.c_str(), meshd::format_name(output.format));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_sample_meshes: %s\n", e.what());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const meshd::Mesh mesh = meshd::testing::structured_square_mesh(20, 20);
  const meshd::ValidityReport report = meshd::check_validity(mesh);
  if (!report.valid()) {
    for (const auto& problem : report.problems) std::fprintf(stderr, "%s\n", problem.c_str());
    return 1;
  }
  const bool square_written = write_all(mesh, dir,
                                        {{"square.msh", meshd::MeshFormat::kMsh41},
                                         {"square_binary.msh", meshd::MeshFormat::kMsh41Binary},
                                         {"square.msh22", meshd::MeshFormat::kMsh22},
                                         {"square.vtu", meshd::MeshFormat::kVtu},
                                         {"square.svg", meshd::MeshFormat::kSvg}});
  if (!square_written) return 1;
  const meshd::TetMesh cube = meshd::testing::structured_cube_mesh(4);
  const meshd::TetValidityReport cube_report = meshd::check_tet_validity(cube);
  if (!cube_report.valid()) {
    std::fprintf(stderr, "%s\n", cube_report.problems[0].c_str());
    return 1;
  }
  const bool cube_written = write_all(cube, dir,
                                      {{"cube.msh", meshd::MeshFormat::kMsh41},
                                       {"cube_binary.msh", meshd::MeshFormat::kMsh41Binary},
                                       {"cube.msh22", meshd::MeshFormat::kMsh22},
                                       {"cube.vtu", meshd::MeshFormat::kVtu}});
  if (!cube_written) return 1;
  std::printf("%zu nodes, %zu triangles, %zu boundary edges\n", mesh.points.size(),
              mesh.triangles.size(), mesh.boundary_edges.size());
  return 0;
}
