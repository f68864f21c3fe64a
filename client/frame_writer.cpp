#include "client/frame_writer.h"

#include <cstdio>
#include <filesystem>

#include "core/common/error.h"
#include "core/mesh/mesh_file.h"

namespace meshd::cli {

FrameWriter::FrameWriter(std::string dir) : dir_(std::move(dir)) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw_invalid("--frames", "cannot create " + dir_ + ": " + error.message());
}

std::string FrameWriter::write(const v1::Snapshot& s) {
  if (s.has_triangles()) {
    triangles_.clear();
    for (int i = 0; i + 2 < s.triangles_size(); i += 3)
      triangles_.push_back({s.triangles(i), s.triangles(i + 1), s.triangles(i + 2)});
  }
  Mesh mesh;
  const int n = s.points_size() / 2;
  for (int i = 0; i < n; ++i) mesh.points.push_back({s.points(2 * i), s.points(2 * i + 1)});
  // Between two retriangulations the points move and the triangles stay; a triangle that names
  // a node this snapshot lacks cannot be drawn.
  for (const auto& t : triangles_) {
    if (t[0] < n && t[1] < n && t[2] < n) mesh.triangles.push_back(t);
  }
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d.svg", s.iteration());
  const std::string path = (std::filesystem::path(dir_) / name).string();
  write_mesh_file(mesh, path, MeshFormat::kSvg);
  ++frames_;
  return path;
}

}  // namespace meshd::cli
