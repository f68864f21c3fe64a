#include "core/mesh3d/tet_validity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/common/error.h"
#include "core/mesh3d/tet_boundary.h"
#include "core/mesh3d/tet_quality.cuh"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

// The corner tetrahedron 0, e1, e2, e3 with its four faces in one group.
TetMesh one_tet() {
  TetMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.tets = {{0, 1, 2, 3}};
  mesh.boundary_faces = tet_boundary_faces(mesh.tets);
  mesh.boundary_tags = {0, 0, 0, 0};
  mesh.boundary_names = {"wall"};
  return mesh;
}

// Adds a tetrahedron with a new corner p, listing its faces that are not (0, 1, 2) as boundary.
void add_tet_on_base(TetMesh& mesh, std::array<int32_t, 3> base, Vec3 p) {
  const auto v = static_cast<int32_t>(mesh.points.size());
  mesh.points.push_back(p);
  mesh.tets.push_back({base[0], base[1], base[2], v});
  for (int k = 0; k < 3; ++k) {
    mesh.boundary_faces.push_back(tet_face(mesh.tets.back(), k));
    mesh.boundary_tags.push_back(0);
  }
}

std::string joined(const TetValidityReport& report) {
  std::string s;
  for (const auto& p : report.problems) s += p + "\n";
  return s;
}

bool contains(const TetValidityReport& report, const std::string& text) {
  return joined(report).find(text) != std::string::npos;
}

TEST(CheckTetValidity, OneTetrahedronIsValid) {
  const TetValidityReport report = check_tet_validity(one_tet());
  EXPECT_TRUE(report.valid()) << joined(report);
  EXPECT_EQ(report.num_points, 4);
  EXPECT_EQ(report.num_tets, 1);
  EXPECT_EQ(report.num_boundary_faces, 4);
  EXPECT_EQ(report.num_interior_faces, 0);
}

TEST(CheckTetValidity, TheStructuredCubeIsValid) {
  const TetMesh mesh = testing::structured_cube_mesh(3);
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_TRUE(report.valid()) << joined(report);
  EXPECT_EQ(report.num_points, 64);
  EXPECT_EQ(report.num_tets, 6 * 27);
  EXPECT_EQ(report.num_boundary_faces, 6 * 2 * 9);
  // Every tetrahedron has four faces: 4 M = F_boundary + 2 F_interior.
  EXPECT_EQ(report.num_interior_faces, (4 * 6 * 27 - 6 * 2 * 9) / 2);
  EXPECT_NEAR(mesh_volume(mesh), 1.0, 1e-12);
}

TEST(CheckTetValidity, ATurnedOverTetrahedronIsReportedByIndex) {
  TetMesh mesh = testing::structured_cube_mesh(2);
  const auto t = mesh.tets[3];
  std::swap(mesh.tets[3][1], mesh.tets[3][2]);
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_inverted, 1);
  EXPECT_EQ(report.first_inverted, 3);
  const std::string name = "tetrahedron 3 (" + std::to_string(t[0]) + ", " + std::to_string(t[2]) +
                           ", " + std::to_string(t[1]) + ", " + std::to_string(t[3]) + ")";
  EXPECT_TRUE(contains(report, name)) << joined(report);
  // Its faces now turn the same way as its neighbours' or against the boundary list.
  EXPECT_GT(report.num_nonconforming_faces + report.num_reversed_boundary_faces, 0);
}

TEST(CheckTetValidity, AFlatTetrahedronIsDegenerateAndAThinOneIsNot) {
  TetMesh mesh = one_tet();
  mesh.points[3] = {0.3, 0.3, 1e-14};  // 6 V / longest^3 = 1e-14 / 1.41^3
  EXPECT_EQ(check_tet_validity(mesh).num_inverted, 1);
  mesh.points[3] = {0.3, 0.3, 1e-6};  // a thin but valid sliver
  EXPECT_EQ(check_tet_validity(mesh).num_inverted, 0);
  EXPECT_EQ(check_tet_validity(mesh, 1e-3).num_inverted, 1);
}

// Four corners near one line (samples along a straight edge): the radius ratio stays about as
// large as 6 V / longest^3, far above a threshold that takes the flat ones near a plane, so an
// engine's filter must ask degenerate_tet, the check's own rule.
TEST(CheckTetValidity, ANeedleIsDegenerateByTheRuleEngineFiltersShare) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{2, 1e-8, 0}, d{3, 0, 1e-8};
  const double ratio = relative_six_volume(a, b, c, d);
  EXPECT_GT(ratio, 0.0);
  EXPECT_LT(ratio, 1e-12);
  EXPECT_GT(oriented_tet_radius_ratio(a, b, c, d), 1e-20);
  EXPECT_TRUE(degenerate_tet(a, b, c, d));
  TetMesh mesh = one_tet();
  mesh.points = {a, b, c, d};
  EXPECT_EQ(check_tet_validity(mesh).num_inverted, 1);

  const Vec3 e1{1, 0, 0}, e2{0, 1, 0}, e3{0, 0, 1};
  EXPECT_NEAR(relative_six_volume(a, e1, e2, e3), 1.0 / (2.0 * std::sqrt(2.0)), 1e-15);
  EXPECT_FALSE(degenerate_tet(a, e1, e2, e3));
  EXPECT_TRUE(degenerate_tet(a, e2, e1, e3));  // turned over
  EXPECT_TRUE(degenerate_tet(a, a, e2, e3));   // two corners coincide
  EXPECT_TRUE(degenerate_tet(a, a, a, a));     // NaN
}

TEST(CheckTetValidity, AnIndexOutOfRangeIsReportedWithoutCrashing) {
  TetMesh mesh = testing::structured_cube_mesh(2);
  mesh.tets[5][2] = 1000;
  mesh.boundary_faces[7][0] = -1;
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_bad_indices, 2);
  EXPECT_TRUE(contains(report,
                       "2 tetrahedra or boundary faces index points outside [0, 27); "
                       "first: tetrahedron 5"))
      << joined(report);
  EXPECT_THROW(check_indices(mesh), Error);
  EXPECT_NO_THROW(check_indices(testing::structured_cube_mesh(2)));
}

TEST(CheckTetValidity, AFaceOfThreeTetrahedraIsNonConforming) {
  TetMesh mesh = one_tet();
  add_tet_on_base(mesh, {0, 2, 1}, {0.2, 0.2, -1});  // below (0, 1, 2): a proper neighbour
  add_tet_on_base(mesh, {0, 2, 1}, {0.3, 0.3, -2});  // and another one
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_inverted, 0) << joined(report);
  EXPECT_EQ(report.num_nonconforming_faces, 1);
  EXPECT_TRUE(contains(report, "face (0, 1, 2) used by 3 tetrahedra")) << joined(report);
}

TEST(CheckTetValidity, TwoTetrahedraOnOneSideOfAFaceAreNonConforming) {
  // The second has its corner inside the first: they overlap, yet both are positive.
  TetMesh mesh = one_tet();
  add_tet_on_base(mesh, {0, 1, 2}, {0.2, 0.2, 0.2});
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_inverted, 0);
  EXPECT_EQ(report.num_nonconforming_faces, 1);
  EXPECT_TRUE(contains(report, "face (0, 1, 2) used by 2 tetrahedra in the same turn"))
      << joined(report);
}

TEST(CheckTetValidity, AnUnusedPointIsReported) {
  TetMesh mesh = one_tet();
  mesh.points.push_back({5, 5, 5});
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_unused_points, 1);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
  EXPECT_TRUE(contains(report, "first: point 4")) << joined(report);
}

TEST(CheckTetValidity, AMissingBoundaryFaceIsReported) {
  TetMesh mesh = testing::structured_cube_mesh(2);
  const auto gone = mesh.boundary_faces.back();
  mesh.boundary_faces.pop_back();
  mesh.boundary_tags.pop_back();
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_missing_boundary_faces, 1);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
  EXPECT_TRUE(contains(report, "missing from boundary_faces")) << joined(report);
  EXPECT_TRUE(contains(report, std::to_string(gone[0]))) << joined(report);
}

TEST(CheckTetValidity, AFaceTurnedInwardIsReportedAndARotatedOneIsFine) {
  TetMesh mesh = one_tet();
  const auto f = mesh.boundary_faces[2];
  mesh.boundary_faces[2] = {f[1], f[2], f[0]};  // the same turn
  EXPECT_TRUE(check_tet_validity(mesh).valid()) << joined(check_tet_validity(mesh));
  mesh.boundary_faces[2] = {f[0], f[2], f[1]};  // the other
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_reversed_boundary_faces, 1);
  EXPECT_EQ(report.num_missing_boundary_faces, 0);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
  EXPECT_TRUE(contains(report, "turned inward")) << joined(report);
  EXPECT_TRUE(contains(report, "first: boundary face 2 (")) << joined(report);
}

TEST(CheckTetValidity, AnInteriorOrRepeatedBoundaryFaceIsReported) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_faces.push_back(tet_face(mesh.tets[0], 0));  // the diagonal's faces are inside
  mesh.boundary_faces.push_back(mesh.boundary_faces[0]);     // listed twice
  mesh.boundary_tags.insert(mesh.boundary_tags.end(), {0, 0});
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_extra_boundary_faces, 2);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
}

TEST(CheckTetValidity, BadTagsAreReported) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_tags[2] = 6;
  TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_bad_tags, 1);
  EXPECT_TRUE(contains(report, "boundary_tags[2] = 6")) << joined(report);
  EXPECT_THROW(check_indices(mesh), Error);

  mesh = testing::structured_cube_mesh(1);
  mesh.boundary_tags.pop_back();
  report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_bad_tags, 1);
  EXPECT_TRUE(contains(report, "boundary_tags has 11 entries for 12 boundary faces"))
      << joined(report);
  try {
    check_indices(mesh);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInternal);
    EXPECT_EQ(e.field(), "mesh");
  }
}

TEST(CheckTetValidity, BadNamesAreReported) {
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_names = {"x0", "x0", "", "domain", "z0", "z1"};
  EXPECT_EQ(check_tet_validity(mesh).num_bad_names, 3);
}

TEST(CheckTetValidity, ANonFinitePointIsReported) {
  TetMesh mesh = one_tet();
  mesh.points[2].z = std::numeric_limits<double>::quiet_NaN();
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_EQ(report.num_nonfinite_points, 1);
  EXPECT_EQ(report.num_inverted, 1);  // a NaN volume fails the volume test too
}

TEST(MeshVolume, SignedSum) {
  TetMesh mesh = one_tet();
  EXPECT_DOUBLE_EQ(mesh_volume(mesh), 1.0 / 6.0);
  std::swap(mesh.tets[0][0], mesh.tets[0][1]);
  EXPECT_DOUBLE_EQ(mesh_volume(mesh), -1.0 / 6.0);
}

}  // namespace
}  // namespace meshd
