// A finished mesh as the service sends it: a serialized meshd.v1.MeshData cut into chunks of at
// most kResultChunkBytes (so that a 1M-node mesh passes a client's default 4 MiB message limit),
// its SHA-256, and the done event's statistics.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/distmesh/distmesh.h"
#include "core/distmesh3d/generate_mesh3d.h"
#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.pb.h"

namespace meshd {

constexpr size_t kResultChunkBytes = size_t{1} << 20;

struct EncodedResult {
  std::vector<std::string> chunks;  // in order; each at most the chunk size, at least one
  uint64_t total_bytes = 0;
  size_t chunk_bytes = kResultChunkBytes;  // every chunk but the last has this size
  v1::Done done;  // sizes, checksum, statistics and quality; backend and device left to the caller
};

v1::MeshData to_mesh_data(const Mesh& mesh);
v1::MeshData to_mesh_data(const TetMesh& mesh);  // dimension 3

// Encodes `result`, cutting the payload into chunks of at most `chunk_bytes` (> 0).
EncodedResult encode_result(const MeshResult& result, size_t chunk_bytes = kResultChunkBytes);
EncodedResult encode_result(const MeshResult3& result, size_t chunk_bytes = kResultChunkBytes);

}  // namespace meshd
