#include "core/mesh3d/tet_validity.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/common/error.h"
#include "core/mesh/mesh_file.h"
#include "core/mesh3d/tet_quality.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

TEST(TetValidity, TheStructuredCubeIsValid) {
  const TetMesh mesh = testing::structured_cube_mesh(3);
  EXPECT_EQ(mesh.points.size(), 64u);
  EXPECT_EQ(mesh.tets.size(), 162u);
  EXPECT_EQ(mesh.boundary_faces.size(), 6u * 2u * 9u);
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_TRUE(report.valid()) << report.problems[0];
  EXPECT_NEAR(summarize_tet_quality(mesh.points, mesh.tets).volume, 1.0, 1e-12);
}

TEST(TetValidity, FindsEachKindOfDefect) {
  const TetMesh good = testing::structured_cube_mesh(2);
  const auto first_problem = [](const TetMesh& m) {
    const TetValidityReport r = check_tet_validity(m);
    return r.valid() ? std::string() : r.problems[0];
  };
  TetMesh turned = good;
  std::swap(turned.tets[3][1], turned.tets[3][2]);
  EXPECT_NE(first_problem(turned).find("volume"), std::string::npos);

  TetMesh unused = good;
  unused.points.push_back({5, 5, 5});
  EXPECT_NE(first_problem(unused).find("unused"), std::string::npos);

  TetMesh missing = good;
  missing.boundary_faces.pop_back();
  missing.boundary_tags.pop_back();
  EXPECT_NE(first_problem(missing).find("not listed"), std::string::npos);

  TetMesh inward = good;
  std::swap(inward.boundary_faces[0][1], inward.boundary_faces[0][2]);
  EXPECT_FALSE(check_tet_validity(inward).valid());

  TetMesh bad_index = good;
  bad_index.tets[0][0] = 1000;
  EXPECT_NE(first_problem(bad_index).find("tets[0]"), std::string::npos);
  EXPECT_THROW(check_indices(bad_index), Error);

  TetMesh bad_tag = good;
  bad_tag.boundary_tags[0] = 6;
  EXPECT_NE(first_problem(bad_tag).find("boundary_tags[0]"), std::string::npos);
}

TEST(TetWriters, HeadersNameTheTetrahedraAndTheGroups) {
  const TetMesh mesh = testing::structured_cube_mesh(1);
  std::ostringstream msh, msh22, vtu;
  write_mesh(mesh, msh, MeshFormat::kMsh41);
  write_mesh(mesh, msh22, MeshFormat::kMsh22);
  write_mesh(mesh, vtu, MeshFormat::kVtu);
  // 8 nodes; 12 boundary triangles in six surfaces, then 6 tetrahedra (type 4) in volume 1.
  EXPECT_NE(msh.str().find("$PhysicalNames\n7\n3 1 \"domain\"\n2 2 \"x0\"\n"), std::string::npos);
  EXPECT_NE(msh.str().find("\n0 0 6 1\n"), std::string::npos);  // entities: surfaces, a volume
  EXPECT_NE(msh.str().find("\n3 1 4 6\n"), std::string::npos);  // the tetrahedra's block
  EXPECT_NE(msh22.str().find("$Elements\n18\n"), std::string::npos);
  EXPECT_NE(vtu.str().find("NumberOfCells=\"18\""), std::string::npos);
  EXPECT_NE(vtu.str().find("Name=\"min_dihedral\""), std::string::npos);
  std::ostringstream svg;
  try {
    write_mesh(mesh, svg, MeshFormat::kSvg);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "format");
  }
}

}  // namespace
}  // namespace meshd
