#include "core/mesh/vtu_writer.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/mesh/quality.h"
#include "tests/core/mesh/file_readers.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

using testing::array_text;
using testing::decode;

std::string write(const Mesh& mesh) {
  std::ostringstream out;
  write_vtu(mesh, out);
  return out.str();
}

TEST(WriteVtu, HeaderDeclaresUInt64HeadersAndTheByteOrder) {
  const std::string file = write(testing::structured_square_mesh(2, 2));
  EXPECT_EQ(file.rfind("<?xml version=\"1.0\"?>\n", 0), 0u);
  EXPECT_NE(file.find("header_type=\"UInt64\""), std::string::npos);
  EXPECT_NE(file.find(std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian"),
            std::string::npos);
  EXPECT_NE(file.find("<Piece NumberOfPoints=\"9\" NumberOfCells=\"16\">"), std::string::npos);
  EXPECT_EQ(file.substr(file.size() - 11), "</VTKFile>\n");
}

TEST(WriteVtu, Base64MatchesKnownEncodingsWithAndWithoutPadding) {
  // One triangle and no boundary: 9-byte types (no padding), 16-byte offsets ("=="), 32-byte
  // connectivity ("="); expected strings from Python's base64 module.
  Mesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}};
  mesh.triangles = {{0, 1, 2}};
  mesh.boundary_edges = {{0, 1}, {1, 2}, {2, 0}};
  mesh.boundary_tags = {0, 0, 0};
  mesh.boundary_names = {"wall"};
  if (std::endian::native != std::endian::little) GTEST_SKIP() << "expected strings are LE";
  const std::string file = write(mesh);
  EXPECT_EQ(array_text(file, "types"), "BAAAAAAAAAAFAwMD");  // 4 cells: 5 3 3 3

  mesh.boundary_edges.clear();
  mesh.boundary_tags.clear();
  const std::string bare = write(mesh);
  EXPECT_EQ(array_text(bare, "offsets"), "CAAAAAAAAAADAAAAAAAAAA==");
  EXPECT_EQ(array_text(bare, "connectivity"), "GAAAAAAAAAAAAAAAAAAAAAEAAAAAAAAAAgAAAAAAAAA=");
}

TEST(WriteVtu, ArraysDecodeBackToTheMesh) {
  const Mesh mesh = testing::structured_square_mesh(6, 5, 3.0, 1.0);
  const size_t num_triangles = mesh.triangles.size(), num_edges = mesh.boundary_edges.size();
  const std::string file = write(mesh);

  const auto points = decode<double>(file, "Points");
  ASSERT_EQ(points.size(), 3 * mesh.points.size());
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    EXPECT_EQ(points[3 * i], mesh.points[i].x);
    EXPECT_EQ(points[3 * i + 1], mesh.points[i].y);
    EXPECT_EQ(points[3 * i + 2], 0.0);
  }

  const auto connectivity = decode<int64_t>(file, "connectivity");
  const auto offsets = decode<int64_t>(file, "offsets");
  const auto types = decode<uint8_t>(file, "types");
  ASSERT_EQ(connectivity.size(), 3 * num_triangles + 2 * num_edges);
  ASSERT_EQ(offsets.size(), num_triangles + num_edges);
  ASSERT_EQ(types.size(), num_triangles + num_edges);
  for (size_t i = 0; i < num_triangles; ++i) {
    EXPECT_EQ(types[i], 5);
    EXPECT_EQ(offsets[i], static_cast<int64_t>(3 * (i + 1)));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(connectivity[3 * i + k], mesh.triangles[i][k]);
  }
  for (size_t i = 0; i < num_edges; ++i) {
    const size_t cell = num_triangles + i;
    EXPECT_EQ(types[cell], 3);
    EXPECT_EQ(offsets[cell], static_cast<int64_t>(3 * num_triangles + 2 * (i + 1)));
    EXPECT_EQ(connectivity[3 * num_triangles + 2 * i], mesh.boundary_edges[i][0]);
    EXPECT_EQ(connectivity[3 * num_triangles + 2 * i + 1], mesh.boundary_edges[i][1]);
  }

  const auto quality = decode<double>(file, "quality");
  const auto min_angle = decode<double>(file, "min_angle");
  const auto physical = decode<int32_t>(file, "physical");
  ASSERT_EQ(quality.size(), num_triangles + num_edges);
  ASSERT_EQ(min_angle.size(), num_triangles + num_edges);
  ASSERT_EQ(physical.size(), num_triangles + num_edges);
  const std::vector<double> expected_quality = triangle_quality(mesh);
  for (size_t i = 0; i < num_triangles; ++i) {
    EXPECT_EQ(quality[i], expected_quality[i]);
    const auto& t = mesh.triangles[i];
    EXPECT_EQ(min_angle[i], min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]));
    EXPECT_EQ(physical[i], kDomainPhysicalTag);
  }
  for (size_t i = num_triangles; i < quality.size(); ++i) {
    EXPECT_TRUE(std::isnan(quality[i]));
    EXPECT_TRUE(std::isnan(min_angle[i]));
    EXPECT_EQ(physical[i], boundary_physical_tag(mesh.boundary_tags[i - num_triangles]));
  }

  EXPECT_EQ(decode<int32_t>(file, "domain"), (std::vector<int32_t>{1, 2}));
  EXPECT_EQ(decode<int32_t>(file, "left"), (std::vector<int32_t>{2, 1}));
  EXPECT_EQ(decode<int32_t>(file, "top"), (std::vector<int32_t>{5, 1}));
}

TEST(WriteVtu, GroupNamesAreEscaped) {
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.boundary_names[0] = "a<b & \"c\"";
  const std::string file = write(mesh);
  EXPECT_NE(file.find("Name=\"a&lt;b &amp; &quot;c&quot;\""), std::string::npos);
}

}  // namespace
}  // namespace meshd
