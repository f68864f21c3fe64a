#include "core/mesh/msh22_writer.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

TEST(WriteMsh22, ParsesBackToTheMesh) {
  const Mesh mesh = testing::structured_square_mesh(3, 2, 1.5, 1.0);
  std::ostringstream out;
  write_msh22(mesh, out);
  std::istringstream in(out.str());

  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "$MeshFormat");
  std::getline(in, line);
  EXPECT_EQ(line, "2.2 0 8");
  std::getline(in, line);
  EXPECT_EQ(line, "$EndMeshFormat");

  std::getline(in, line);
  EXPECT_EQ(line, "$PhysicalNames");
  int num_names;
  in >> num_names;
  ASSERT_EQ(num_names, 5);
  std::getline(in, line);
  const std::vector<std::string> names = {"2 1 \"domain\"", "1 2 \"left\"", "1 3 \"right\"",
                                          "1 4 \"bottom\"", "1 5 \"top\""};
  for (const auto& expected : names) {
    std::getline(in, line);
    EXPECT_EQ(line, expected);
  }
  std::getline(in, line);
  EXPECT_EQ(line, "$EndPhysicalNames");

  std::getline(in, line);
  EXPECT_EQ(line, "$Nodes");
  size_t num_nodes;
  in >> num_nodes;
  ASSERT_EQ(num_nodes, mesh.points.size());
  for (size_t i = 0; i < num_nodes; ++i) {
    size_t number;
    double x, y, z;
    in >> number >> x >> y >> z;
    EXPECT_EQ(number, i + 1);
    EXPECT_EQ(x, mesh.points[i].x);
    EXPECT_EQ(y, mesh.points[i].y);
    EXPECT_EQ(z, 0.0);
  }
  in >> line;
  EXPECT_EQ(line, "$EndNodes");

  in >> line;
  EXPECT_EQ(line, "$Elements");
  size_t num_elements;
  in >> num_elements;
  ASSERT_EQ(num_elements, mesh.boundary_edges.size() + mesh.triangles.size());
  std::vector<int> lines_per_physical(6, 0);
  std::vector<std::array<int32_t, 3>> triangles;
  for (size_t k = 0; k < num_elements; ++k) {
    size_t number;
    int type, num_tags, physical, elementary;
    in >> number >> type >> num_tags >> physical >> elementary;
    EXPECT_EQ(number, k + 1);
    EXPECT_EQ(num_tags, 2);
    if (type == 1) {
      int a, b;
      in >> a >> b;
      ASSERT_TRUE(physical >= 2 && physical <= 5);
      EXPECT_EQ(elementary, physical - 1);
      ++lines_per_physical[physical];
      // The line is the boundary edge it claims to be, with its group.
      bool found = false;
      for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
        found |= mesh.boundary_edges[i] == std::array<int32_t, 2>{a - 1, b - 1} &&
                 mesh.boundary_tags[i] + 2 == physical;
      }
      EXPECT_TRUE(found);
    } else {
      ASSERT_EQ(type, 2);
      EXPECT_EQ(physical, 1);
      EXPECT_EQ(elementary, 1);
      int a, b, c;
      in >> a >> b >> c;
      triangles.push_back({a - 1, b - 1, c - 1});
    }
  }
  EXPECT_EQ(triangles, mesh.triangles);
  EXPECT_EQ(lines_per_physical, (std::vector<int>{0, 0, 2, 2, 3, 3}));
  in >> line;
  EXPECT_EQ(line, "$EndElements");
  EXPECT_FALSE(in.fail());
}

TEST(WriteMsh22, BadTagThrows) {
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.boundary_tags[0] = 7;
  std::ostringstream out;
  EXPECT_THROW(write_msh22(mesh, out), Error);
}

}  // namespace
}  // namespace meshd
