#include "client/result_assembly.h"

#include "core/common/error.h"
#include "core/common/sha256.h"
#include "meshd/v1/mesh.pb.h"

namespace meshd::cli {

void ResultAssembly::add(const v1::ResultChunk& chunk) {
  if (chunk.index() != next_index_ || chunk.offset() != payload_.size()) {
    throw Error(ErrorCode::kInternal, "result",
                "chunk " + std::to_string(chunk.index()) + " arrived out of order");
  }
  ++next_index_;
  payload_ += chunk.data();
}

std::variant<Mesh, TetMesh> ResultAssembly::finish(const v1::Done& done) const {
  if (payload_.size() != done.result_bytes()) {
    throw Error(ErrorCode::kInternal, "result",
                "received " + std::to_string(payload_.size()) + " bytes, the server sent " +
                    std::to_string(done.result_bytes()));
  }
  if (sha256_hex(payload_) != done.result_sha256())
    throw Error(ErrorCode::kInternal, "result", "the SHA-256 of the received mesh differs");
  v1::MeshData data;
  if (!data.ParseFromString(payload_))
    throw Error(ErrorCode::kInternal, "result", "the received mesh does not parse");
  if (data.dimension() == 3) return to_tet_mesh(data);
  return to_mesh(data);
}

namespace {

// An index into `count` nodes or groups, or Error(kInternal) naming what it indexes.
int32_t checked_index(int32_t v, size_t count, const char* what) {
  if (v < 0 || static_cast<size_t>(v) >= count)
    throw Error(ErrorCode::kInternal, "result", std::string(what) + " index out of range");
  return v;
}

}  // namespace

TetMesh to_tet_mesh(const v1::MeshData& data) {
  TetMesh mesh;
  const int n = data.points_size() / 3;
  mesh.points.reserve(n);
  for (int i = 0; i < n; ++i)
    mesh.points.push_back({data.points(3 * i), data.points(3 * i + 1), data.points(3 * i + 2)});
  const auto node = [n](int32_t v) { return checked_index(v, static_cast<size_t>(n), "node"); };
  for (int i = 0; i + 3 < data.tetrahedra_size(); i += 4) {
    mesh.tets.push_back({node(data.tetrahedra(i)), node(data.tetrahedra(i + 1)),
                         node(data.tetrahedra(i + 2)), node(data.tetrahedra(i + 3))});
  }
  for (int i = 0; i + 2 < data.boundary_faces_size(); i += 3) {
    mesh.boundary_faces.push_back({node(data.boundary_faces(i)), node(data.boundary_faces(i + 1)),
                                   node(data.boundary_faces(i + 2))});
  }
  mesh.boundary_names.assign(data.boundary_names().begin(), data.boundary_names().end());
  for (int32_t tag : data.boundary_tags())
    mesh.boundary_tags.push_back(checked_index(tag, mesh.boundary_names.size(), "boundary tag"));
  if (mesh.boundary_tags.size() != mesh.boundary_faces.size())
    throw Error(ErrorCode::kInternal, "result", "boundary tags and faces differ in number");
  return mesh;
}

Mesh to_mesh(const v1::MeshData& data) {
  Mesh mesh;
  const int n = data.points_size() / 2;
  mesh.points.reserve(n);
  for (int i = 0; i < n; ++i) mesh.points.push_back({data.points(2 * i), data.points(2 * i + 1)});
  auto index = [n](int32_t v) {
    if (v < 0 || v >= n) throw Error(ErrorCode::kInternal, "result", "node index out of range");
    return v;
  };
  for (int i = 0; i + 2 < data.triangles_size(); i += 3) {
    mesh.triangles.push_back(
        {index(data.triangles(i)), index(data.triangles(i + 1)), index(data.triangles(i + 2))});
  }
  for (int i = 0; i + 1 < data.boundary_edges_size(); i += 2)
    mesh.boundary_edges.push_back(
        {index(data.boundary_edges(i)), index(data.boundary_edges(i + 1))});
  mesh.boundary_tags.assign(data.boundary_tags().begin(), data.boundary_tags().end());
  mesh.boundary_names.assign(data.boundary_names().begin(), data.boundary_names().end());
  for (int32_t tag : mesh.boundary_tags) {
    if (tag < 0 || tag >= static_cast<int32_t>(mesh.boundary_names.size()))
      throw Error(ErrorCode::kInternal, "result", "boundary tag out of range");
  }
  return mesh;
}

}  // namespace meshd::cli
