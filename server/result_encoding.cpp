#include "server/result_encoding.h"

#include <algorithm>
#include <utility>

#include "core/common/sha256.h"
#include "server/mesh_payload.h"

namespace meshd {

v1::MeshData to_mesh_data(const Mesh& mesh) {
  v1::MeshData out;
  out.mutable_points()->Reserve(static_cast<int>(2 * mesh.points.size()));
  for (const Vec2& p : mesh.points) {
    out.add_points(p.x);
    out.add_points(p.y);
  }
  out.mutable_triangles()->Reserve(static_cast<int>(3 * mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    for (int32_t v : t) out.add_triangles(v);
  }
  for (const auto& e : mesh.boundary_edges) {
    out.add_boundary_edges(e[0]);
    out.add_boundary_edges(e[1]);
  }
  for (int32_t tag : mesh.boundary_tags) out.add_boundary_tags(tag);
  for (const auto& name : mesh.boundary_names) out.add_boundary_names(name);
  return out;
}

v1::MeshData to_mesh_data(const TetMesh& mesh) {
  v1::MeshData out;
  out.set_dimension(3);
  out.mutable_points()->Reserve(static_cast<int>(3 * mesh.points.size()));
  for (const Vec3& p : mesh.points) {
    out.add_points(p.x);
    out.add_points(p.y);
    out.add_points(p.z);
  }
  out.mutable_tetrahedra()->Reserve(static_cast<int>(4 * mesh.tets.size()));
  for (const auto& t : mesh.tets) {
    for (int32_t v : t) out.add_tetrahedra(v);
  }
  for (const auto& f : mesh.boundary_faces) {
    for (int32_t v : f) out.add_boundary_faces(v);
  }
  for (int32_t tag : mesh.boundary_tags) out.add_boundary_tags(tag);
  for (const auto& name : mesh.boundary_names) out.add_boundary_names(name);
  return out;
}

namespace {

v1::RunStats to_proto(const RunStats3& s) {
  v1::RunStats out;
  out.set_iterations(s.iterations);
  out.set_converged(s.converged);
  out.set_levels(1);
  out.set_retriangulations(s.retriangulations);
  out.set_full_triangulations(s.retriangulations - s.partial_retriangulations -
                              s.repaired_retriangulations);
  out.set_density_removed(s.removed);
  out.set_t_triangulation(s.t_triangulation);
  out.set_t_forces(s.t_steps);
  out.set_fixed_nodes(s.fixed);
  out.set_sliver_moves(s.optimizer_moves);
  out.set_t_slivers(s.t_slivers);
  out.set_t_mesh(s.t_total);
  return out;
}

v1::Quality to_proto(const TetQualityStats& q) {
  v1::Quality out;
  out.set_q_min(q.q_min);
  out.set_q_mean(q.q_mean);
  for (int64_t count : q.histogram) out.add_histogram(count);
  out.set_min_dihedral_deg(q.min_dihedral_deg);
  out.set_max_dihedral_deg(q.max_dihedral_deg);
  out.set_volume(q.volume);
  out.set_max_surface_offset(q.max_surface_offset);
  return out;
}

// The payload with its size and checksum in `done`.
EncodedResult checksummed(std::shared_ptr<const ResultPayload> payload) {
  EncodedResult out;
  out.done.set_result_bytes(payload->bytes.size());
  out.done.set_result_sha256(sha256_hex(payload->bytes));
  out.payload = std::move(payload);
  return out;
}

template <typename AnyMesh>
std::shared_ptr<const ResultPayload> payload_of(const AnyMesh& mesh, ThreadPool* pool,
                                                size_t chunk_bytes) {
  auto out = std::make_shared<ResultPayload>();
  out->bytes = mesh_payload(mesh, pool);
  out->chunk_bytes = chunk_bytes;
  return out;
}

v1::RunStats to_proto(const RunStats& s) {
  v1::RunStats out;
  out.set_iterations(s.iterations);
  out.set_converged(s.converged);
  out.set_levels(s.levels);
  out.set_retriangulations(s.retriangulations);
  out.set_full_triangulations(s.full_triangulations);
  out.set_flips(s.flips);
  out.set_repair_fallbacks(s.repair_fallbacks);
  out.set_fold_refills(s.fold_refills);
  out.set_density_removed(s.density_removed);
  out.set_cleanup_removed(s.cleanup_removed);
  out.set_trapped_removed(s.trapped_removed);
  out.set_t_triangulation(s.t_triangulation);
  out.set_t_forces(s.t_forces);
  out.set_t_cleanup(s.t_cleanup);
  out.set_t_mesh(s.t_total);
  return out;
}

v1::Quality to_proto(const QualityStats& q) {
  v1::Quality out;
  out.set_q_min(q.q_min);
  out.set_q_mean(q.q_mean);
  out.set_min_angle_deg(q.min_angle_deg);
  for (int64_t count : q.histogram) out.add_histogram(count);
  return out;
}

}  // namespace

size_t ResultPayload::chunk_count() const {
  return std::max<size_t>(1, (bytes.size() + chunk_bytes - 1) / chunk_bytes);
}

std::string_view ResultPayload::chunk(size_t i) const {
  return std::string_view(bytes).substr(i * chunk_bytes, chunk_bytes);
}

std::shared_ptr<const ResultPayload> encode_payload(const MeshResult& result, ThreadPool* pool,
                                                    size_t chunk_bytes) {
  return payload_of(result.mesh, pool, chunk_bytes);
}

std::shared_ptr<const ResultPayload> encode_payload(const MeshResult3& result, ThreadPool* pool,
                                                    size_t chunk_bytes) {
  return payload_of(result.mesh, pool, chunk_bytes);
}

EncodedResult encode_done(const MeshResult& result, std::shared_ptr<const ResultPayload> payload) {
  EncodedResult out = checksummed(std::move(payload));
  v1::Done& done = out.done;
  done.set_nodes(static_cast<int64_t>(result.mesh.points.size()));
  done.set_triangles(static_cast<int64_t>(result.mesh.triangles.size()));
  done.set_boundary_edges(static_cast<int64_t>(result.mesh.boundary_edges.size()));
  *done.mutable_stats() = to_proto(result.stats);
  *done.mutable_quality() = to_proto(result.quality);
  return out;
}

EncodedResult encode_done(const MeshResult3& result, std::shared_ptr<const ResultPayload> payload) {
  EncodedResult out = checksummed(std::move(payload));
  v1::Done& done = out.done;
  done.set_nodes(static_cast<int64_t>(result.mesh.points.size()));
  done.set_tetrahedra(static_cast<int64_t>(result.mesh.tets.size()));
  done.set_boundary_faces(static_cast<int64_t>(result.mesh.boundary_faces.size()));
  *done.mutable_stats() = to_proto(result.stats);
  *done.mutable_quality() = to_proto(result.quality);
  return out;
}

}  // namespace meshd
