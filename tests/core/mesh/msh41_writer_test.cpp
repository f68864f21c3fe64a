#include "core/mesh/msh41_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "tests/core/mesh/file_readers.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

using testing::BinaryReader;
using testing::section;

std::string write(const Mesh& mesh, MshEncoding encoding) {
  std::ostringstream out(std::ios::binary);
  write_msh41(mesh, out, encoding);
  return out.str();
}

// ---- ASCII -------------------------------------------------------------------------------------

TEST(WriteMsh41Ascii, SectionsParseBackToTheMesh) {
  const Mesh mesh = testing::structured_square_mesh(4, 3, 2.0, 0.3);
  const std::string file = write(mesh, MshEncoding::kAscii);

  EXPECT_EQ(section(file, "MeshFormat"), "4.1 0 8\n");
  EXPECT_EQ(section(file, "PhysicalNames"),
            "5\n2 1 \"domain\"\n1 2 \"left\"\n1 3 \"right\"\n1 4 \"bottom\"\n1 5 \"top\"\n");

  // Entities: 0 points, 4 curves, 1 surface; each curve in its group, the surface in the domain.
  std::istringstream entities(section(file, "Entities"));
  int num_points, num_curves, num_surfaces, num_volumes;
  entities >> num_points >> num_curves >> num_surfaces >> num_volumes;
  EXPECT_EQ(num_points, 0);
  ASSERT_EQ(num_curves, 4);
  EXPECT_EQ(num_surfaces, 1);
  EXPECT_EQ(num_volumes, 0);
  for (int g = 0; g < 4; ++g) {
    int tag, num_physicals, physical, num_bounding;
    double box[6];
    entities >> tag;
    for (double& v : box) entities >> v;
    entities >> num_physicals >> physical >> num_bounding;
    EXPECT_EQ(tag, g + 1);
    EXPECT_EQ(num_physicals, 1);
    EXPECT_EQ(physical, g + 2);
    EXPECT_EQ(num_bounding, 0);
    if (g == testing::kRight) {
      EXPECT_EQ(box[0], 2.0);  // min x of the right side
      EXPECT_EQ(box[4], 0.3);  // max y
    }
  }
  int surface_tag, num_physicals, physical, num_bounding;
  double box[6];
  entities >> surface_tag;
  for (double& v : box) entities >> v;
  entities >> num_physicals >> physical >> num_bounding;
  EXPECT_EQ(surface_tag, 1);
  EXPECT_EQ(physical, 1);
  EXPECT_EQ(num_bounding, 4);
  EXPECT_EQ(box[3], 2.0);

  // Nodes: one block in surface 1, tags 1..N, then exact coordinates.
  std::istringstream nodes(section(file, "Nodes"));
  size_t num_blocks, num_nodes, min_tag, max_tag;
  nodes >> num_blocks >> num_nodes >> min_tag >> max_tag;
  EXPECT_EQ(num_blocks, 1u);
  ASSERT_EQ(num_nodes, mesh.points.size());
  EXPECT_EQ(min_tag, 1u);
  EXPECT_EQ(max_tag, mesh.points.size());
  int dim, entity, parametric;
  size_t in_block;
  nodes >> dim >> entity >> parametric >> in_block;
  EXPECT_EQ(dim, 2);
  EXPECT_EQ(entity, 1);
  EXPECT_EQ(parametric, 0);
  EXPECT_EQ(in_block, num_nodes);
  for (size_t i = 0; i < num_nodes; ++i) {
    size_t tag;
    nodes >> tag;
    EXPECT_EQ(tag, i + 1);
  }
  for (size_t i = 0; i < num_nodes; ++i) {
    double x, y, z;
    nodes >> x >> y >> z;
    EXPECT_EQ(x, mesh.points[i].x);  // shortest round-trip text: exact
    EXPECT_EQ(y, mesh.points[i].y);
    EXPECT_EQ(z, 0.0);
  }
  EXPECT_FALSE(nodes.fail());

  // Elements: 4 line blocks (one per group), then the triangles; tags consecutive.
  std::istringstream elements(section(file, "Elements"));
  size_t num_element_blocks, num_elements, min_element, max_element;
  elements >> num_element_blocks >> num_elements >> min_element >> max_element;
  EXPECT_EQ(num_element_blocks, 5u);
  ASSERT_EQ(num_elements, mesh.boundary_edges.size() + mesh.triangles.size());
  EXPECT_EQ(min_element, 1u);
  EXPECT_EQ(max_element, num_elements);
  size_t next_tag = 1;
  std::map<int, std::vector<std::array<int32_t, 2>>> lines;
  std::vector<std::array<int32_t, 3>> triangles;
  for (size_t b = 0; b < num_element_blocks; ++b) {
    int element_dim, element_entity, type;
    size_t count;
    elements >> element_dim >> element_entity >> type >> count;
    const int nodes_per = type == 1 ? 2 : 3;
    EXPECT_EQ(element_dim, type);  // lines are dimension 1, triangles 2
    for (size_t k = 0; k < count; ++k) {
      size_t tag, v[3];
      elements >> tag;
      EXPECT_EQ(tag, next_tag++);
      for (int j = 0; j < nodes_per; ++j) elements >> v[j];
      if (type == 1) {
        lines[element_entity - 1].push_back({int32_t(v[0] - 1), int32_t(v[1] - 1)});
      } else {
        triangles.push_back({int32_t(v[0] - 1), int32_t(v[1] - 1), int32_t(v[2] - 1)});
      }
    }
  }
  EXPECT_FALSE(elements.fail());
  EXPECT_EQ(triangles, mesh.triangles);
  for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
    const auto& group = lines[mesh.boundary_tags[i]];
    EXPECT_NE(std::find(group.begin(), group.end(), mesh.boundary_edges[i]), group.end());
  }
  size_t total_lines = 0;
  for (const auto& [group, edges] : lines) total_lines += edges.size();
  EXPECT_EQ(total_lines, mesh.boundary_edges.size());
}

TEST(WriteMsh41Ascii, EmptyGroupKeepsItsNameAndEntityButNoBlock) {
  Mesh mesh = testing::structured_square_mesh(2, 2);
  mesh.boundary_names.push_back("unused");
  const std::string file = write(mesh, MshEncoding::kAscii);
  EXPECT_NE(section(file, "PhysicalNames").find("1 6 \"unused\""), std::string::npos);
  EXPECT_EQ(section(file, "Entities").substr(0, 8), "0 5 1 0\n");
  EXPECT_EQ(section(file, "Elements").substr(0, 2), "5 ");  // 4 line blocks + triangles
}

TEST(WriteMsh41Ascii, QuoteInNameIsReplaced) {
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.boundary_names[0] = "say \"hi\"";
  EXPECT_NE(write(mesh, MshEncoding::kAscii).find("1 2 \"say _hi_\"\n"), std::string::npos);
}

TEST(WriteMsh41, BadIndicesThrow) {
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.triangles[0][2] = 99;
  EXPECT_THROW(write(mesh, MshEncoding::kAscii), Error);
  EXPECT_THROW(write(mesh, MshEncoding::kBinary), Error);
}

// ---- Binary ------------------------------------------------------------------------------------

TEST(WriteMsh41Binary, BlocksParseBackToTheMesh) {
  const Mesh mesh = testing::structured_square_mesh(5, 4, 1.0, 0.7);
  const std::string file = write(mesh, MshEncoding::kBinary);
  const size_t num_points = mesh.points.size();

  // Header: ASCII line, then the int 1, then a newline.
  const std::string header = "$MeshFormat\n4.1 1 8\n";
  ASSERT_EQ(file.compare(0, header.size(), header), 0);
  BinaryReader r(file, header.size());
  EXPECT_EQ(r.integer(), 1);
  EXPECT_TRUE(r.expect("\n$EndMeshFormat\n"));

  // $PhysicalNames stays ASCII.
  const std::string names =
      "$PhysicalNames\n5\n2 1 \"domain\"\n1 2 \"left\"\n1 3 \"right\"\n1 4 \"bottom\"\n"
      "1 5 \"top\"\n$EndPhysicalNames\n";
  ASSERT_TRUE(r.expect(names));

  ASSERT_TRUE(r.expect("$Entities\n"));
  EXPECT_EQ(r.size(), 0u);
  EXPECT_EQ(r.size(), 4u);
  EXPECT_EQ(r.size(), 1u);
  EXPECT_EQ(r.size(), 0u);
  for (int g = 0; g < 4; ++g) {
    EXPECT_EQ(r.integer(), g + 1);
    for (int k = 0; k < 6; ++k) r.real();
    EXPECT_EQ(r.size(), 1u);
    EXPECT_EQ(r.integer(), g + 2);
    EXPECT_EQ(r.size(), 0u);  // no bounding points
  }
  EXPECT_EQ(r.integer(), 1);
  EXPECT_EQ(r.real(), 0.0);  // min x
  EXPECT_EQ(r.real(), 0.0);  // min y
  EXPECT_EQ(r.real(), 0.0);  // min z
  EXPECT_EQ(r.real(), 1.0);  // max x
  EXPECT_EQ(r.real(), 0.7);  // max y
  EXPECT_EQ(r.real(), 0.0);  // max z
  EXPECT_EQ(r.size(), 1u);
  EXPECT_EQ(r.integer(), 1);
  EXPECT_EQ(r.size(), 4u);
  for (int g = 0; g < 4; ++g) EXPECT_EQ(r.integer(), g + 1);
  ASSERT_TRUE(r.expect("\n$EndEntities\n"));

  ASSERT_TRUE(r.expect("$Nodes\n"));
  EXPECT_EQ(r.size(), 1u);
  EXPECT_EQ(r.size(), num_points);
  EXPECT_EQ(r.size(), 1u);
  EXPECT_EQ(r.size(), num_points);
  EXPECT_EQ(r.integer(), 2);
  EXPECT_EQ(r.integer(), 1);
  EXPECT_EQ(r.integer(), 0);
  EXPECT_EQ(r.size(), num_points);
  for (size_t i = 0; i < num_points; ++i) EXPECT_EQ(r.size(), i + 1);
  for (size_t i = 0; i < num_points; ++i) {
    EXPECT_EQ(r.real(), mesh.points[i].x);
    EXPECT_EQ(r.real(), mesh.points[i].y);
    EXPECT_EQ(r.real(), 0.0);
  }
  ASSERT_TRUE(r.expect("\n$EndNodes\n"));

  ASSERT_TRUE(r.expect("$Elements\n"));
  const uint64_t num_elements = mesh.boundary_edges.size() + mesh.triangles.size();
  EXPECT_EQ(r.size(), 5u);
  EXPECT_EQ(r.size(), num_elements);
  EXPECT_EQ(r.size(), 1u);
  EXPECT_EQ(r.size(), num_elements);
  uint64_t tag = 1;
  size_t num_lines = 0;
  for (int g = 0; g < 4; ++g) {
    EXPECT_EQ(r.integer(), 1);
    EXPECT_EQ(r.integer(), g + 1);
    EXPECT_EQ(r.integer(), 1);  // 2-node line
    const uint64_t count = r.size();
    EXPECT_EQ(count, static_cast<uint64_t>(g < 2 ? 4 : 5));  // left/right 4, bottom/top 5
    for (uint64_t k = 0; k < count; ++k) {
      EXPECT_EQ(r.size(), tag++);
      const int32_t a = static_cast<int32_t>(r.size() - 1), b = static_cast<int32_t>(r.size() - 1);
      bool found = false;
      for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
        found |=
            mesh.boundary_edges[i] == std::array<int32_t, 2>{a, b} && mesh.boundary_tags[i] == g;
      }
      EXPECT_TRUE(found) << a << " " << b;
      ++num_lines;
    }
  }
  EXPECT_EQ(num_lines, mesh.boundary_edges.size());
  EXPECT_EQ(r.integer(), 2);
  EXPECT_EQ(r.integer(), 1);
  EXPECT_EQ(r.integer(), 2);  // 3-node triangle
  EXPECT_EQ(r.size(), mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    EXPECT_EQ(r.size(), tag++);
    for (const int32_t v : t) EXPECT_EQ(r.size(), static_cast<uint64_t>(v) + 1);
  }
  ASSERT_TRUE(r.expect("\n$EndElements\n"));
  EXPECT_EQ(r.position(), file.size());
}

TEST(WriteMsh41, EmptyMeshIsWellFormed) {
  Mesh mesh;
  const std::string ascii = write(mesh, MshEncoding::kAscii);
  EXPECT_EQ(section(ascii, "Nodes"), "0 0 0 0\n");
  EXPECT_EQ(section(ascii, "Elements"), "0 0 0 0\n");
  EXPECT_EQ(section(ascii, "PhysicalNames"), "1\n2 1 \"domain\"\n");
}

}  // namespace
}  // namespace meshd
