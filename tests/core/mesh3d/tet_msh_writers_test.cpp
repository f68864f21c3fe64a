// The MSH 4.1 (ASCII and binary) and MSH 2.2 writers on tetrahedra: every section read back,
// independently of the writers, to the mesh that was written.
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "core/mesh/msh22_writer.h"
#include "core/mesh/msh41_writer.h"
#include "tests/core/mesh/file_readers.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

using testing::BinaryReader;
using testing::section;

using Face = std::array<int32_t, 3>;

std::string write41(const TetMesh& mesh, MshEncoding encoding) {
  std::ostringstream out(std::ios::binary);
  write_msh41(mesh, out, encoding);
  return out.str();
}

// The ASCII twin of BinaryReader: the values of one section, separated by white space.
class AsciiValues {
 public:
  explicit AsciiValues(const std::string& text) : in_(text) {}
  uint64_t size() { return get<uint64_t>(); }
  int32_t integer() { return get<int32_t>(); }
  double real() { return get<double>(); }
  bool ok() const { return !in_.fail(); }

 private:
  template <typename T>
  T get() {
    T v{};
    in_ >> v;
    return v;
  }
  std::istringstream in_;
};

// What $Entities, $Nodes and $Elements of a MSH 4.1 file say, in either encoding.
struct Msh41Body {
  std::vector<uint64_t> entity_counts;  // points, curves, surfaces, volumes
  std::vector<int32_t> surface_physicals;
  std::vector<int32_t> volume_physicals, volume_bounds;
  std::vector<Vec3> points;
  std::vector<std::array<int32_t, 4>> tets;
  std::map<int32_t, std::vector<Face>> faces;  // by surface entity tag
  std::vector<uint64_t> element_tags;
};

template <typename Values>
void read_entities(Values& v, Msh41Body& body) {
  for (int d = 0; d < 4; ++d) body.entity_counts.push_back(v.size());
  for (uint64_t s = 0; s < body.entity_counts[2]; ++s) {
    EXPECT_EQ(v.integer(), static_cast<int32_t>(s + 1));
    for (int k = 0; k < 6; ++k) v.real();  // the box
    for (uint64_t n = v.size(); n > 0; --n) body.surface_physicals.push_back(v.integer());
    EXPECT_EQ(v.size(), 0u);  // no bounding curves
  }
  for (uint64_t s = 0; s < body.entity_counts[3]; ++s) {
    EXPECT_EQ(v.integer(), 1);
    const double box[6] = {v.real(), v.real(), v.real(), v.real(), v.real(), v.real()};
    EXPECT_EQ(std::vector<double>(box, box + 6), (std::vector<double>{0, 0, 0, 1, 1, 1}));
    for (uint64_t n = v.size(); n > 0; --n) body.volume_physicals.push_back(v.integer());
    for (uint64_t n = v.size(); n > 0; --n) body.volume_bounds.push_back(v.integer());
  }
}

template <typename Values>
void read_nodes(Values& v, Msh41Body& body) {
  const uint64_t blocks = v.size(), count = v.size();
  EXPECT_EQ(blocks, 1u);
  EXPECT_EQ(v.size(), 1u);     // smallest tag
  EXPECT_EQ(v.size(), count);  // largest
  EXPECT_EQ(v.integer(), 3);   // in the volume
  EXPECT_EQ(v.integer(), 1);
  EXPECT_EQ(v.integer(), 0);  // not parametric
  EXPECT_EQ(v.size(), count);
  for (uint64_t i = 0; i < count; ++i) EXPECT_EQ(v.size(), i + 1);
  for (uint64_t i = 0; i < count; ++i) body.points.push_back({v.real(), v.real(), v.real()});
}

template <typename Values>
void read_elements(Values& v, Msh41Body& body) {
  const uint64_t blocks = v.size(), count = v.size();
  EXPECT_EQ(v.size(), 1u);
  EXPECT_EQ(v.size(), count);
  for (uint64_t b = 0; b < blocks; ++b) {
    const int32_t dim = v.integer(), entity = v.integer(), type = v.integer();
    EXPECT_EQ(type, dim == 3 ? 4 : 2);  // 4-node tetrahedra, 3-node triangles
    for (uint64_t n = v.size(); n > 0; --n) {
      body.element_tags.push_back(v.size());
      const auto node = [&] { return static_cast<int32_t>(v.size()) - 1; };
      if (dim == 3) {
        body.tets.push_back({node(), node(), node(), node()});
      } else {
        body.faces[entity].push_back({node(), node(), node()});
      }
    }
  }
}

// Checks body against the mesh it was written from.
void expect_mesh(const Msh41Body& body, const TetMesh& mesh) {
  const int groups = static_cast<int>(mesh.boundary_names.size());
  EXPECT_EQ(body.entity_counts, (std::vector<uint64_t>{0, 0, static_cast<uint64_t>(groups), 1}));
  std::vector<int32_t> physicals, bounds;
  for (int g = 0; g < groups; ++g) {
    physicals.push_back(g + 2);
    bounds.push_back(g + 1);
  }
  EXPECT_EQ(body.surface_physicals, physicals);
  EXPECT_EQ(body.volume_physicals, std::vector<int32_t>{1});
  EXPECT_EQ(body.volume_bounds, bounds);
  EXPECT_EQ(body.points, mesh.points);  // shortest round-trip text: exact
  EXPECT_EQ(body.tets, mesh.tets);
  std::map<int32_t, std::vector<Face>> faces;  // in the mesh's order within each group
  for (size_t i = 0; i < mesh.boundary_faces.size(); ++i)
    faces[mesh.boundary_tags[i] + 1].push_back(mesh.boundary_faces[i]);
  EXPECT_EQ(body.faces, faces);
  ASSERT_EQ(body.element_tags.size(), mesh.boundary_faces.size() + mesh.tets.size());
  for (size_t i = 0; i < body.element_tags.size(); ++i) EXPECT_EQ(body.element_tags[i], i + 1);
}

const char kCubeNames[] =
    "7\n3 1 \"domain\"\n2 2 \"x0\"\n2 3 \"x1\"\n2 4 \"y0\"\n2 5 \"y1\"\n2 6 \"z0\"\n2 7 \"z1\"\n";

TEST(WriteTetMsh41Ascii, SectionsParseBackToTheMesh) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  const std::string file = write41(mesh, MshEncoding::kAscii);
  EXPECT_EQ(section(file, "MeshFormat"), "4.1 0 8\n");
  EXPECT_EQ(section(file, "PhysicalNames"), kCubeNames);
  EXPECT_EQ(section(file, "Entities").substr(0, 8), "0 0 6 1\n");
  EXPECT_EQ(section(file, "Nodes").substr(0, 19), "1 27 1 27\n3 1 0 27\n");
  // 6 blocks of 8 triangles, then the 48 tetrahedra in volume 1.
  EXPECT_EQ(section(file, "Elements").substr(0, 18), "7 96 1 96\n2 1 2 8\n");
  EXPECT_NE(file.find("\n3 1 4 48\n49 "), std::string::npos);

  Msh41Body body;
  AsciiValues entities(section(file, "Entities")), nodes(section(file, "Nodes")),
      elements(section(file, "Elements"));
  read_entities(entities, body);
  read_nodes(nodes, body);
  read_elements(elements, body);
  EXPECT_TRUE(entities.ok() && nodes.ok() && elements.ok());
  expect_mesh(body, mesh);
}

TEST(WriteTetMsh41Binary, BlocksParseBackToTheMesh) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  const std::string file = write41(mesh, MshEncoding::kBinary);
  const std::string header = "$MeshFormat\n4.1 1 8\n";
  ASSERT_EQ(file.compare(0, header.size(), header), 0);
  BinaryReader r(file, header.size());
  EXPECT_EQ(r.integer(), 1);  // the byte order
  ASSERT_TRUE(r.expect("\n$EndMeshFormat\n"));
  ASSERT_TRUE(r.expect(std::string("$PhysicalNames\n") + kCubeNames + "$EndPhysicalNames\n"));
  Msh41Body body;
  ASSERT_TRUE(r.expect("$Entities\n"));
  read_entities(r, body);
  ASSERT_TRUE(r.expect("\n$EndEntities\n$Nodes\n"));
  read_nodes(r, body);
  ASSERT_TRUE(r.expect("\n$EndNodes\n$Elements\n"));
  read_elements(r, body);
  ASSERT_TRUE(r.expect("\n$EndElements\n"));
  EXPECT_EQ(r.position(), file.size());
  expect_mesh(body, mesh);
}

TEST(WriteTetMsh41, AnEmptyGroupKeepsItsNameAndEntityButNoBlock) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_names.push_back("unused");
  const std::string file = write41(mesh, MshEncoding::kAscii);
  EXPECT_NE(section(file, "PhysicalNames").find("2 8 \"unused\"\n"), std::string::npos);
  EXPECT_EQ(section(file, "Entities").substr(0, 8), "0 0 7 1\n");
  EXPECT_EQ(section(file, "Elements").substr(0, 2), "7 ");  // 6 triangle blocks + tetrahedra
}

TEST(WriteTetMsh22, ElementsCarryTheirGroupsAndTypes) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  std::ostringstream out;
  write_msh22(mesh, out);
  const std::string file = out.str();
  EXPECT_EQ(section(file, "MeshFormat"), "2.2 0 8\n");
  EXPECT_EQ(section(file, "PhysicalNames"), kCubeNames);

  std::istringstream nodes(section(file, "Nodes"));
  size_t count = 0;
  nodes >> count;
  ASSERT_EQ(count, mesh.points.size());
  for (size_t i = 0; i < count; ++i) {
    size_t number;
    Vec3 p;
    nodes >> number >> p.x >> p.y >> p.z;
    EXPECT_EQ(number, i + 1);
    EXPECT_EQ(p, mesh.points[i]);
  }

  // The triangles grouped by group in the mesh's order, as MSH 4.1 numbers them, then the
  // tetrahedra; each with its physical and elementary tags.
  std::vector<std::vector<int64_t>> expected;
  for (int g = 0; g < 6; ++g)
    for (size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
      if (mesh.boundary_tags[i] != g) continue;
      const Face& f = mesh.boundary_faces[i];
      expected.push_back({2, 2, g + 2, g + 1, f[0] + 1, f[1] + 1, f[2] + 1});
    }
  for (const auto& t : mesh.tets)
    expected.push_back({4, 2, 1, 1, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1});
  std::istringstream elements(section(file, "Elements"));
  elements >> count;
  ASSERT_EQ(count, expected.size());
  for (size_t i = 0; i < count; ++i) {
    int64_t number;
    elements >> number;
    EXPECT_EQ(number, static_cast<int64_t>(i + 1));
    std::vector<int64_t> fields(expected[i].size());
    for (int64_t& f : fields) elements >> f;
    EXPECT_EQ(fields, expected[i]) << "element " << i + 1;
  }
  EXPECT_FALSE(elements.fail());
}

TEST(WriteTetMsh, BadIndicesThrow) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.tets[2][3] = 8;
  std::ostringstream out;
  EXPECT_THROW(write_msh41(mesh, out, MshEncoding::kAscii), Error);
  EXPECT_THROW(write_msh41(mesh, out, MshEncoding::kBinary), Error);
  EXPECT_THROW(write_msh22(mesh, out), Error);
  mesh = testing::structured_cube_mesh(1);
  mesh.boundary_tags[0] = 6;
  EXPECT_THROW(write_msh22(mesh, out), Error);
}

}  // namespace
}  // namespace meshd
