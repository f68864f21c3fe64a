#include "core/mesh/boundary.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

using Edges = std::vector<std::array<int32_t, 2>>;

TEST(BoundaryEdgesOf, SingleTriangleGivesItsEdgesInOrder) {
  EXPECT_EQ(boundary_edges_of({{4, 7, 9}}), (Edges{{4, 7}, {7, 9}, {9, 4}}));
}

TEST(BoundaryEdgesOf, SharedEdgeIsInterior) {
  // Unit square split along the diagonal 0-2.
  EXPECT_EQ(boundary_edges_of({{0, 1, 2}, {0, 2, 3}}), (Edges{{0, 1}, {1, 2}, {2, 3}, {3, 0}}));
}

TEST(BoundaryEdgesOf, EdgeUsedThreeTimesIsNotBoundary) {
  const Edges edges = boundary_edges_of({{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  EXPECT_EQ(std::count(edges.begin(), edges.end(), std::array<int32_t, 2>{0, 1}), 0);
  EXPECT_EQ(edges.size(), 6u);
}

TEST(BoundaryEdgesOf, EmptyInput) { EXPECT_TRUE(boundary_edges_of({}).empty()); }

TEST(BoundaryEdgesOf, StructuredMeshMatchesItsBoundaryList) {
  const Mesh mesh = testing::structured_square_mesh(7, 5);
  Edges expected = mesh.boundary_edges;
  Edges actual = boundary_edges_of(mesh.triangles);
  ASSERT_EQ(actual.size(), 2u * (7 + 5));
  std::sort(expected.begin(), expected.end());
  std::sort(actual.begin(), actual.end());
  EXPECT_EQ(actual, expected);
}

TEST(BoundaryHalfEdges, IncreasingIdsWhoseEndsAreTheBoundaryEdges) {
  const Mesh mesh = testing::structured_square_mesh(7, 5);
  const std::vector<int32_t> ids = boundary_half_edges(mesh.triangles);
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_EQ(half_edge_ends(mesh.triangles, ids), boundary_edges_of(mesh.triangles));
  EXPECT_EQ(boundary_half_edges({{0, 1, 2}, {0, 2, 3}}), (std::vector<int32_t>{0, 1, 4, 5}));
}

TEST(BoundaryHalfEdges, TurningATriangleOverMapsKToTwoMinusK) {
  // assemble_mesh relies on it: the boundary found before the triangles are made
  // counter-clockwise serves after.
  std::vector<std::array<int32_t, 3>> tris = testing::structured_square_mesh(3, 2).triangles;
  const std::vector<int32_t> before = boundary_half_edges(tris);
  for (size_t t = 0; t < tris.size(); t += 3) std::swap(tris[t][1], tris[t][2]);
  std::vector<int32_t> mapped;
  for (int32_t id : before) mapped.push_back(id / 3 % 3 == 0 ? 3 * (id / 3) + 2 - id % 3 : id);
  std::sort(mapped.begin(), mapped.end());
  EXPECT_EQ(boundary_half_edges(tris), mapped);
}

}  // namespace
}  // namespace meshd
