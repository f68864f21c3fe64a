#include "client/result_assembly.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/common/error.h"
#include "meshd/v1/mesh.pb.h"

namespace meshd::cli {

namespace {

constexpr uint64_t kMaxPayload = std::numeric_limits<int32_t>::max();

// Error(kInternal) naming what `flat` indexes unless every entry is below `count`.
void check_indices(const google::protobuf::RepeatedField<int32_t>& flat, size_t count,
                   const char* what) {
  for (const int32_t v : flat) {
    if (v < 0 || static_cast<size_t>(v) >= count)
      throw Error(ErrorCode::kInternal, "result", std::string(what) + " index out of range");
  }
}

// The whole K-tuples of `flat`, checked against `count` nodes, in one pass and one copy (a
// million-node mesh has 6M indices).
template <size_t K>
std::vector<std::array<int32_t, K>> node_tuples(
    const google::protobuf::RepeatedField<int32_t>& flat, size_t count) {
  check_indices(flat, count, "node");
  std::vector<std::array<int32_t, K>> out(static_cast<size_t>(flat.size()) / K);
  if (!out.empty()) std::memcpy(out.data(), flat.data(), out.size() * sizeof(out[0]));
  return out;
}

}  // namespace

void ResultAssembly::add(const v1::ResultChunk& chunk) {
  if (chunk.index() != next_index_ || chunk.offset() != payload_.size()) {
    throw Error(ErrorCode::kInternal, "result",
                "chunk " + std::to_string(chunk.index()) + " arrived out of order");
  }
  // The whole payload's room at once: growing it chunk by chunk copies it again and again.
  // protobuf parses at most 2 GiB, so no more is reserved whatever the server says.
  if (chunk.index() == 0) payload_.reserve(std::min<uint64_t>(chunk.total_bytes(), kMaxPayload));
  ++next_index_;
  payload_ += chunk.data();
  sha_.update(chunk.data());
}

std::variant<Mesh, TetMesh> ResultAssembly::finish(const v1::Done& done) const {
  if (payload_.size() != done.result_bytes()) {
    throw Error(ErrorCode::kInternal, "result",
                "received " + std::to_string(payload_.size()) + " bytes, the server sent " +
                    std::to_string(done.result_bytes()));
  }
  if (sha_.hex() != done.result_sha256())
    throw Error(ErrorCode::kInternal, "result", "the SHA-256 of the received mesh differs");
  v1::MeshData data;
  if (!data.ParseFromString(payload_))
    throw Error(ErrorCode::kInternal, "result", "the received mesh does not parse");
  if (data.dimension() == 3) return to_tet_mesh(data);
  return to_mesh(data);
}

TetMesh to_tet_mesh(const v1::MeshData& data) {
  TetMesh mesh;
  const double* p = data.points().data();
  mesh.points.resize(static_cast<size_t>(data.points_size()) / 3);
  for (size_t i = 0; i < mesh.points.size(); ++i)
    mesh.points[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  const size_t n = mesh.points.size();
  mesh.tets = node_tuples<4>(data.tetrahedra(), n);
  mesh.boundary_faces = node_tuples<3>(data.boundary_faces(), n);
  mesh.boundary_names.assign(data.boundary_names().begin(), data.boundary_names().end());
  check_indices(data.boundary_tags(), mesh.boundary_names.size(), "boundary tag");
  mesh.boundary_tags.assign(data.boundary_tags().begin(), data.boundary_tags().end());
  if (mesh.boundary_tags.size() != mesh.boundary_faces.size())
    throw Error(ErrorCode::kInternal, "result", "boundary tags and faces differ in number");
  return mesh;
}

Mesh to_mesh(const v1::MeshData& data) {
  Mesh mesh;
  const double* p = data.points().data();
  mesh.points.resize(static_cast<size_t>(data.points_size()) / 2);
  for (size_t i = 0; i < mesh.points.size(); ++i) mesh.points[i] = {p[2 * i], p[2 * i + 1]};
  const size_t n = mesh.points.size();
  mesh.triangles = node_tuples<3>(data.triangles(), n);
  mesh.boundary_edges = node_tuples<2>(data.boundary_edges(), n);
  mesh.boundary_names.assign(data.boundary_names().begin(), data.boundary_names().end());
  check_indices(data.boundary_tags(), mesh.boundary_names.size(), "boundary tag");
  mesh.boundary_tags.assign(data.boundary_tags().begin(), data.boundary_tags().end());
  return mesh;
}

}  // namespace meshd::cli
