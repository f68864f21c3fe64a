// The VTU writer on tetrahedra: cells, types and cell data decoded back, independently of the
// writer.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "core/mesh/vtu_writer.h"
#include "core/mesh3d/tet_quality.h"
#include "tests/core/mesh/file_readers.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

using testing::decode;

std::string write(const TetMesh& mesh) {
  std::ostringstream out;
  write_vtu(mesh, out);
  return out.str();
}

TEST(WriteTetVtu, HeaderCountsTetrahedraAndBoundaryTriangles) {
  const std::string file = write(testing::structured_cube_mesh(1));
  EXPECT_EQ(file.rfind("<?xml version=\"1.0\"?>\n", 0), 0u);
  // 8 points; 6 tetrahedra and 12 boundary triangles.
  EXPECT_NE(file.find("<Piece NumberOfPoints=\"8\" NumberOfCells=\"18\">"), std::string::npos);
  EXPECT_NE(file.find("<CellData Scalars=\"quality\">"), std::string::npos);
  EXPECT_NE(file.find("Name=\"min_dihedral\""), std::string::npos);
  EXPECT_EQ(file.find("Name=\"min_angle\""), std::string::npos);
  EXPECT_EQ(file.substr(file.size() - 11), "</VTKFile>\n");
}

TEST(WriteTetVtu, ArraysDecodeBackToTheMesh) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  const size_t num_tets = mesh.tets.size(), num_faces = mesh.boundary_faces.size();
  const std::string file = write(mesh);

  const auto points = decode<double>(file, "Points");
  ASSERT_EQ(points.size(), 3 * mesh.points.size());
  for (size_t i = 0; i < mesh.points.size(); ++i)
    EXPECT_EQ((Vec3{points[3 * i], points[3 * i + 1], points[3 * i + 2]}), mesh.points[i]);

  const auto connectivity = decode<int64_t>(file, "connectivity");
  const auto offsets = decode<int64_t>(file, "offsets");
  const auto types = decode<uint8_t>(file, "types");
  ASSERT_EQ(connectivity.size(), 4 * num_tets + 3 * num_faces);
  ASSERT_EQ(offsets.size(), num_tets + num_faces);
  ASSERT_EQ(types.size(), num_tets + num_faces);
  for (size_t i = 0; i < num_tets; ++i) {
    EXPECT_EQ(types[i], 10);  // VTK_TETRA
    EXPECT_EQ(offsets[i], static_cast<int64_t>(4 * (i + 1)));
    for (int k = 0; k < 4; ++k) EXPECT_EQ(connectivity[4 * i + k], mesh.tets[i][k]);
  }
  for (size_t i = 0; i < num_faces; ++i) {
    const size_t cell = num_tets + i;
    EXPECT_EQ(types[cell], 5);  // VTK_TRIANGLE
    EXPECT_EQ(offsets[cell], static_cast<int64_t>(4 * num_tets + 3 * (i + 1)));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(connectivity[4 * num_tets + 3 * i + k], mesh.boundary_faces[i][k]);
  }

  const auto quality = decode<double>(file, "quality");
  const auto min_dihedral = decode<double>(file, "min_dihedral");
  const auto physical = decode<int32_t>(file, "physical");
  ASSERT_EQ(quality.size(), num_tets + num_faces);
  ASSERT_EQ(min_dihedral.size(), num_tets + num_faces);
  ASSERT_EQ(physical.size(), num_tets + num_faces);
  const std::vector<double> expected_quality = tet_quality(mesh);
  for (size_t i = 0; i < num_tets; ++i) {
    EXPECT_EQ(quality[i], expected_quality[i]);
    EXPECT_NEAR(min_dihedral[i], 45.0, 1e-9);  // every Kuhn tetrahedron's
    EXPECT_EQ(physical[i], kDomainPhysicalTag);
  }
  for (size_t i = num_tets; i < quality.size(); ++i) {
    EXPECT_TRUE(std::isnan(quality[i]));
    EXPECT_TRUE(std::isnan(min_dihedral[i]));
    EXPECT_EQ(physical[i], boundary_physical_tag(mesh.boundary_tags[i - num_tets]));
  }

  // {tag, dimension}: the domain is a volume, the groups are surfaces.
  EXPECT_EQ(decode<int32_t>(file, "domain"), (std::vector<int32_t>{1, 3}));
  EXPECT_EQ(decode<int32_t>(file, "x0"), (std::vector<int32_t>{2, 2}));
  EXPECT_EQ(decode<int32_t>(file, "z1"), (std::vector<int32_t>{7, 2}));
}

TEST(WriteTetVtu, BadIndicesThrow) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_faces[3][1] = -2;
  EXPECT_THROW(write(mesh), Error);
}

}  // namespace
}  // namespace meshd
