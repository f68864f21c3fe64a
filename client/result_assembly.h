// Puts a job's result back together on the client: the chunks in order, checked against the
// done event's size and SHA-256, parsed into the mesh arrays that core/mesh's writers take.
#pragma once

#include <string>

#include "core/mesh/mesh.h"
#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.pb.h"

namespace meshd::cli {

class ResultAssembly {
 public:
  // Throws Error(kInternal) when a chunk arrives out of order.
  void add(const v1::ResultChunk& chunk);
  // Checks the payload against `done` and converts it. Throws Error(kInternal) naming
  // "result" when the size or the checksum differ or the payload does not parse.
  Mesh finish(const v1::Done& done) const;

 private:
  std::string payload_;
  uint32_t next_index_ = 0;
};

// The mesh arrays of a MeshData. Throws Error(kInternal) when an index is out of range.
Mesh to_mesh(const v1::MeshData& data);

}  // namespace meshd::cli
