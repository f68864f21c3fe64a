// Puts a job's result back together on the client: the chunks in order, checked against the
// done event's size and SHA-256, parsed into the mesh arrays that core/mesh's writers take. Each
// chunk is hashed as it arrives, so the check overlaps the transfer.
#pragma once

#include <string>
#include <variant>

#include "core/common/sha256.h"
#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"
#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.pb.h"

namespace meshd::cli {

class ResultAssembly {
 public:
  // Throws Error(kInternal) when a chunk arrives out of order.
  void add(const v1::ResultChunk& chunk);
  // Checks the payload against `done` and converts it: a Mesh, or a TetMesh for a 3D result.
  // Throws Error(kInternal) naming "result" when the size or the checksum differ or the payload
  // does not parse.
  std::variant<Mesh, TetMesh> finish(const v1::Done& done) const;

 private:
  std::string payload_;
  Sha256 sha_;
  uint32_t next_index_ = 0;
};

// The mesh arrays of a MeshData (dimension 2, or unset). Throws Error(kInternal) when an index
// is out of range.
Mesh to_mesh(const v1::MeshData& data);
// The same for a 3D MeshData (dimension 3).
TetMesh to_tet_mesh(const v1::MeshData& data);

}  // namespace meshd::cli
