#include "client/frame_writer.h"

#include <cstdio>
#include <filesystem>

#include "core/common/error.h"
#include "core/mesh/mesh_file.h"
#include "core/mesh3d/tet_boundary.h"

namespace meshd::cli {
namespace {

// The cells of a snapshot's flat list, #M by K.
template <size_t K>
void read_cells(const google::protobuf::RepeatedField<int32_t>& flat,
                std::vector<std::array<int32_t, K>>& cells) {
  cells.clear();
  for (int i = 0; i + static_cast<int>(K) <= flat.size(); i += static_cast<int>(K)) {
    std::array<int32_t, K> c;
    for (size_t k = 0; k < K; ++k) c[k] = flat[i + static_cast<int>(k)];
    cells.push_back(c);
  }
}

// Between two retriangulations the points move and the cells stay; a cell that names a node
// this snapshot lacks cannot be drawn.
template <size_t K>
bool drawable(const std::array<int32_t, K>& cell, int nodes) {
  for (int32_t v : cell)
    if (v < 0 || v >= nodes) return false;
  return true;
}

}  // namespace

FrameWriter::FrameWriter(std::string dir) : dir_(std::move(dir)) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw_invalid("--frames", "cannot create " + dir_ + ": " + error.message());
}

std::string FrameWriter::write(const v1::Snapshot& s) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.svg", s.iteration());
  const std::string path = (std::filesystem::path(dir_) / name).string();
  if (s.dimension() == 3)
    write_volume(s, path);
  else
    write_plane(s, path);
  ++frames_;
  return path;
}

void FrameWriter::write_plane(const v1::Snapshot& s, const std::string& path) {
  if (s.has_triangles()) read_cells(s.triangles(), triangles_);
  Mesh mesh;
  const int n = s.points_size() / 2;
  for (int i = 0; i < n; ++i) mesh.points.push_back({s.points(2 * i), s.points(2 * i + 1)});
  for (const auto& t : triangles_)
    if (drawable(t, n)) mesh.triangles.push_back(t);
  write_mesh_file(mesh, path, MeshFormat::kSvg);
}

void FrameWriter::write_volume(const v1::Snapshot& s, const std::string& path) {
  if (s.has_tetrahedra()) read_cells(s.tetrahedra(), tetrahedra_);
  TetMesh mesh;
  const int n = s.points_size() / 3;
  for (int i = 0; i < n; ++i)
    mesh.points.push_back({s.points(3 * i), s.points(3 * i + 1), s.points(3 * i + 2)});
  for (const auto& t : tetrahedra_)
    if (drawable(t, n)) mesh.tets.push_back(t);
  // The picture is of the surface: the faces of one tetrahedron each, in one group.
  mesh.boundary_faces = tet_boundary_faces(mesh.tets);
  mesh.boundary_tags.assign(mesh.boundary_faces.size(), 0);
  mesh.boundary_names = {"boundary"};
  write_mesh_file(mesh, path, MeshFormat::kSvg);
}

}  // namespace meshd::cli
