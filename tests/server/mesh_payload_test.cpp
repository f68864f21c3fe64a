#include "server/mesh_payload.h"

#include <gtest/gtest.h>

#include <random>

#include "server/result_encoding.h"

namespace meshd {
namespace {

// Random arrays long enough for several pieces, indices of every varint length (1 to 5 bytes,
// and negative ones of 10, which no mesh has but the encoding allows).
Mesh random_mesh(size_t triangles, std::mt19937& rng) {
  Mesh m;
  std::uniform_real_distribution<double> x(-1e6, 1e6);
  std::uniform_int_distribution<int> bits(0, 31);
  auto index = [&] {
    const int32_t v = static_cast<int32_t>(rng() & ((uint32_t{1} << bits(rng)) - 1));
    return rng() % 1000 == 0 ? -v - 1 : v;
  };
  for (size_t i = 0; i < triangles / 2 + 3; ++i) m.points.push_back({x(rng), x(rng)});
  for (size_t i = 0; i < triangles; ++i) m.triangles.push_back({index(), index(), index()});
  for (size_t i = 0; i < triangles / 10; ++i) {
    m.boundary_edges.push_back({index(), index()});
    m.boundary_tags.push_back(index());
  }
  m.boundary_names = {"outer", "", "hole 1"};
  return m;
}

TEST(MeshPayload, BytesAreTheMessagesSerialization) {
  std::mt19937 rng(7);
  ThreadPool pool(3);
  for (const size_t triangles : {size_t{0}, size_t{1}, size_t{1'000}, size_t{200'000}}) {
    const Mesh m = random_mesh(triangles, rng);
    const std::string reference = to_mesh_data(m).SerializeAsString();
    EXPECT_EQ(mesh_payload(m, nullptr), reference) << triangles;
    EXPECT_EQ(mesh_payload(m, &pool), reference) << triangles;
  }
  EXPECT_EQ(mesh_payload(Mesh{}, &pool), "");
}

TEST(MeshPayload, AVolumesBytesAreTheMessagesSerialization) {
  std::mt19937 rng(11);
  ThreadPool pool(3);
  std::uniform_real_distribution<double> x(-1.0, 1.0);
  for (const int tets : {0, 5, 100'000}) {
    TetMesh m;
    for (int i = 0; i < tets / 4 + 4; ++i) m.points.push_back({x(rng), x(rng), x(rng)});
    const auto node = [&] { return static_cast<int32_t>(rng() % m.points.size()); };
    for (int i = 0; i < tets; ++i) m.tets.push_back({node(), node(), node(), node()});
    for (int i = 0; i < tets / 8; ++i) {
      m.boundary_faces.push_back({node(), node(), node()});
      m.boundary_tags.push_back(static_cast<int32_t>(i % 2));
    }
    m.boundary_names = {"ball", "box"};
    const std::string reference = to_mesh_data(m).SerializeAsString();
    EXPECT_EQ(mesh_payload(m, nullptr), reference) << tets;
    EXPECT_EQ(mesh_payload(m, &pool), reference) << tets;
  }
}

}  // namespace
}  // namespace meshd
