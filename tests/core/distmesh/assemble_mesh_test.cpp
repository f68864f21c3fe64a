// assemble_mesh: unused nodes dropped, triangles made counter-clockwise, and the boundary found
// by the caller before that (boundary_half_edges) given in the order and orientation of the
// result.
#include "core/distmesh/assemble_mesh.h"

#include <gtest/gtest.h>

#include "core/distmesh/compiled_problem.h"
#include "core/mesh/boundary.h"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

TEST(AssembleMesh, TurnedTrianglesKeepTheirBoundaryInTheResultsOrder) {
  const CompiledProblem c = compile_problem(testing::benchmark_problem("G2", 0.1));
  // A fan around node 5 of a square's corners and side midpoints; node 0 is unused. Triangles
  // 1 and 3 are clockwise.
  const std::vector<Vec2> points = {{0, 0},  {-1, -1}, {1, -1}, {1, 1},
                                    {-1, 1}, {0, 0},   {0, -1}, {0, 1}};
  const std::vector<std::array<int32_t, 3>> triangles = {{5, 1, 6}, {5, 2, 6}, {5, 2, 3},
                                                         {5, 7, 3}, {5, 7, 4}, {5, 4, 1}};
  const Mesh mesh = assemble_mesh(c, points, triangles, boundary_half_edges(triangles));
  ASSERT_EQ(mesh.points.size(), 7u);
  for (const auto& t : mesh.triangles) {
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], d = mesh.points[t[2]];
    EXPECT_GT(cross(b - a, d - a), 0.0);
  }
  EXPECT_EQ(mesh.boundary_edges, boundary_edges_of(mesh.triangles));
  ASSERT_EQ(mesh.boundary_edges.size(), 6u);
  ASSERT_EQ(mesh.boundary_tags.size(), 6u);
  ASSERT_EQ(mesh.boundary_names, (std::vector<std::string>{"outer"}));
}

// A copy the engine vouches for as tidy moves in as it is, with the boundary and tags that the
// full assembly gives.
TEST(AssembleMesh, ATidyCopyGivesTheSameMeshAsTheFullAssembly) {
  const CompiledProblem c = compile_problem(testing::benchmark_problem("G2", 0.1));
  const std::vector<Vec2> points = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, 0}};
  const std::vector<std::array<int32_t, 3>> triangles = {
      {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const std::vector<int32_t> boundary = boundary_half_edges(triangles);
  const Mesh full = assemble_mesh(c, points, triangles, boundary, false);
  const Mesh tidy = assemble_mesh(c, points, triangles, boundary, true);
  EXPECT_EQ(tidy.points.size(), full.points.size());
  EXPECT_EQ(tidy.triangles, full.triangles);
  EXPECT_EQ(tidy.boundary_edges, full.boundary_edges);
  EXPECT_EQ(tidy.boundary_tags, full.boundary_tags);
  EXPECT_EQ(tidy.boundary_names, full.boundary_names);
}

}  // namespace
}  // namespace meshd
