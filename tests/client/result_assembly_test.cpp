// The client's half of a result's journey: the chunks the server's encoding cuts, put back
// together, checked and converted to the same mesh arrays.
#include "client/result_assembly.h"

#include <gtest/gtest.h>

#include <string>

#include "core/common/error.h"
#include "server/result_encoding.h"

namespace meshd::cli {
namespace {

// A strip of `n` by 2 nodes in triangles, its two long sides as two boundary groups.
MeshResult strip(int n) {
  MeshResult r;
  for (int i = 0; i < n; ++i) {
    r.mesh.points.push_back({0.5 * i, 0.0});
    r.mesh.points.push_back({0.5 * i + 0.25, 1.0 / 3.0});
  }
  for (int i = 0; i + 1 < n; ++i) {
    const int a = 2 * i;
    r.mesh.triangles.push_back({a, a + 2, a + 1});
    r.mesh.triangles.push_back({a + 1, a + 2, a + 3});
    r.mesh.boundary_edges.push_back({a, a + 2});
    r.mesh.boundary_tags.push_back(0);
    r.mesh.boundary_edges.push_back({a + 3, a + 1});
    r.mesh.boundary_tags.push_back(1);
  }
  r.mesh.boundary_names = {"bottom", "top"};
  return r;
}

// Every chunk of `encoded` in order, each as its own event carries it.
void add_all(ResultAssembly& assembly, const EncodedResult& encoded) {
  const ResultPayload& payload = *encoded.payload;
  for (size_t i = 0; i < payload.chunk_count(); ++i) {
    v1::ResultChunk c;
    c.set_index(static_cast<uint32_t>(i));
    c.set_count(static_cast<uint32_t>(payload.chunk_count()));
    c.set_offset(i * payload.chunk_bytes);
    c.set_total_bytes(payload.bytes.size());
    const std::string_view data = payload.chunk(i);
    c.set_data(data.data(), data.size());
    assembly.add(c);
  }
}

TEST(ResultAssembly, ChunksGoBackToTheSameMesh) {
  const MeshResult r = strip(2'000);
  for (const size_t chunk_bytes : {size_t{1} << 16, size_t{4'096}, size_t{7}}) {
    const EncodedResult encoded = encode_result(r, nullptr, chunk_bytes);
    ASSERT_GT(encoded.payload->chunk_count(), 1u) << chunk_bytes;
    ResultAssembly assembly;
    add_all(assembly, encoded);
    const Mesh mesh = std::get<Mesh>(assembly.finish(encoded.done));
    ASSERT_EQ(mesh.points.size(), r.mesh.points.size());
    for (size_t i = 0; i < mesh.points.size(); ++i) {
      EXPECT_EQ(mesh.points[i].x, r.mesh.points[i].x);
      EXPECT_EQ(mesh.points[i].y, r.mesh.points[i].y);
    }
    EXPECT_EQ(mesh.triangles, r.mesh.triangles);
    EXPECT_EQ(mesh.boundary_edges, r.mesh.boundary_edges);
    EXPECT_EQ(mesh.boundary_tags, r.mesh.boundary_tags);
    EXPECT_EQ(mesh.boundary_names, r.mesh.boundary_names);
  }
}

TEST(ResultAssembly, AnEmptyMeshIsOneEmptyChunk) {
  const EncodedResult encoded = encode_result(MeshResult{}, nullptr);
  ASSERT_EQ(encoded.payload->chunk_count(), 1u);
  EXPECT_TRUE(encoded.payload->chunk(0).empty());
  ResultAssembly assembly;
  add_all(assembly, encoded);
  EXPECT_TRUE(std::get<Mesh>(assembly.finish(encoded.done)).points.empty());
}

TEST(ResultAssembly, ADifferentChecksumOrSizeIsRefused) {
  const EncodedResult encoded = encode_result(strip(100), nullptr, 64);
  ResultAssembly assembly;
  add_all(assembly, encoded);
  v1::Done wrong_sha = encoded.done;
  wrong_sha.set_result_sha256(std::string(64, '0'));
  EXPECT_THROW(assembly.finish(wrong_sha), Error);
  v1::Done wrong_size = encoded.done;
  wrong_size.set_result_bytes(encoded.payload->bytes.size() + 1);
  EXPECT_THROW(assembly.finish(wrong_size), Error);
  EXPECT_NO_THROW(assembly.finish(encoded.done));
}

TEST(ResultAssembly, ChunksOutOfOrderAreRefused) {
  const EncodedResult encoded = encode_result(strip(100), nullptr, 64);
  ResultAssembly assembly;
  v1::ResultChunk second;
  second.set_index(1);
  second.set_offset(64);
  second.set_data(std::string(encoded.payload->chunk(1)));
  EXPECT_THROW(assembly.add(second), Error);
}

TEST(ResultAssembly, IndicesOutOfRangeAreRefused) {
  v1::MeshData data = to_mesh_data(strip(10).mesh);
  EXPECT_NO_THROW(to_mesh(data));
  data.set_triangles(5, 20);  // 20 nodes: 0 to 19
  EXPECT_THROW(to_mesh(data), Error);
  data = to_mesh_data(strip(10).mesh);
  data.set_boundary_edges(0, -1);
  EXPECT_THROW(to_mesh(data), Error);
  data = to_mesh_data(strip(10).mesh);
  data.set_boundary_tags(3, 2);  // two groups
  EXPECT_THROW(to_mesh(data), Error);
}

}  // namespace
}  // namespace meshd::cli
