// A finished mesh's payload: the bytes of a serialized meshd.v1.MeshData, written straight from
// the mesh arrays, the long packed fields in pieces over a thread pool. A 100k-node result is
// 3 MB: building the message and serializing it took 5 ms of one host thread, and its memory
// was touched twice. The bytes are those of to_mesh_data(mesh).SerializeAsString() (a test
// holds the two together).
#pragma once

#include <string>

#include "core/common/thread_pool.h"
#include "core/mesh/mesh.h"
#include "core/mesh3d/tet_mesh.h"

namespace meshd {

// `pool` may be null: then all on the caller's thread, with the same bytes.
std::string mesh_payload(const Mesh& mesh, ThreadPool* pool);
std::string mesh_payload(const TetMesh& mesh, ThreadPool* pool);  // dimension 3

}  // namespace meshd
