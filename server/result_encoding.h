// A finished mesh as the service sends it: a serialized meshd.v1.MeshData cut into chunks of at
// most kResultChunkBytes (so that a 1M-node mesh passes a client's default 4 MiB message limit),
// its SHA-256, and the done event's statistics.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "core/common/thread_pool.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh3d/generate_mesh3d.h"
#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.pb.h"

namespace meshd {

constexpr size_t kResultChunkBytes = size_t{1} << 20;

// A serialized MeshData, held once and shared: a job's streams send views of it, from before
// the worker has taken its checksum.
struct ResultPayload {
  std::string bytes;
  size_t chunk_bytes = kResultChunkBytes;  // every chunk but the last has this size

  // At least one, the last maybe empty (an empty payload is one empty chunk).
  size_t chunk_count() const;
  // Chunk i < chunk_count(), in order: at offset i * chunk_bytes, at most chunk_bytes long.
  std::string_view chunk(size_t i) const;
};

struct EncodedResult {
  std::shared_ptr<const ResultPayload> payload;
  v1::Done done;  // sizes, checksum, statistics and quality; backend and device left to the caller
};

// The mesh as a message: the reference for the payload that encode_result writes straight
// from the arrays (server/mesh_payload.h), and for tests that alter a result field by field.
v1::MeshData to_mesh_data(const Mesh& mesh);
v1::MeshData to_mesh_data(const TetMesh& mesh);  // dimension 3

// The payload of `result`, written over `pool` (may be null), sent in chunks of at most
// `chunk_bytes` (> 0).
std::shared_ptr<const ResultPayload> encode_payload(const MeshResult& result, ThreadPool* pool,
                                                    size_t chunk_bytes = kResultChunkBytes);
std::shared_ptr<const ResultPayload> encode_payload(const MeshResult3& result, ThreadPool* pool,
                                                    size_t chunk_bytes = kResultChunkBytes);

// `result` with its `payload` (from encode_payload) and the done event, with the checksum.
EncodedResult encode_done(const MeshResult& result, std::shared_ptr<const ResultPayload> payload);
EncodedResult encode_done(const MeshResult3& result, std::shared_ptr<const ResultPayload> payload);

// Both at once.
template <typename Result>
EncodedResult encode_result(const Result& result, ThreadPool* pool,
                            size_t chunk_bytes = kResultChunkBytes) {
  return encode_done(result, encode_payload(result, pool, chunk_bytes));
}

}  // namespace meshd
