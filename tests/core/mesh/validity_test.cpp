#include "core/mesh/validity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/common/error.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

// The unit square as two triangles with one boundary group per side.
Mesh two_triangle_square() {
  Mesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.boundary_edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  mesh.boundary_tags = {0, 1, 2, 3};
  mesh.boundary_names = {"bottom", "right", "top", "left"};
  return mesh;
}

std::string joined(const ValidityReport& report) {
  std::string s;
  for (const auto& p : report.problems) s += p + "\n";
  return s;
}

TEST(CheckValidity, TwoTriangleSquareIsValid) {
  const ValidityReport report = check_validity(two_triangle_square());
  EXPECT_TRUE(report.valid()) << joined(report);
  EXPECT_EQ(report.num_points, 4);
  EXPECT_EQ(report.num_triangles, 2);
  EXPECT_EQ(report.num_boundary_edges, 4);
  EXPECT_EQ(report.num_interior_edges, 1);
}

TEST(CheckValidity, StructuredMeshIsValid) {
  const Mesh mesh = testing::structured_square_mesh(20, 13, 2.0, 3.0);
  const ValidityReport report = check_validity(mesh);
  EXPECT_TRUE(report.valid()) << joined(report);
  EXPECT_EQ(report.num_boundary_edges, 2 * (20 + 13));
  // Euler: E = (3 M + E_boundary) / 2 for a triangulated disc.
  EXPECT_EQ(report.num_interior_edges, (3 * 2 * 20 * 13 - 2 * (20 + 13)) / 2);
  EXPECT_NEAR(mesh_area(mesh), 6.0, 1e-12);
}

TEST(CheckValidity, ClockwiseTriangleIsReportedByIndex) {
  Mesh mesh = two_triangle_square();
  mesh.triangles[1] = {0, 3, 2};
  const ValidityReport report = check_validity(mesh);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(report.num_inverted, 1);
  EXPECT_EQ(report.first_inverted, 1);
  EXPECT_NE(joined(report).find("triangle 1 (0, 3, 2)"), std::string::npos) << joined(report);
}

TEST(CheckValidity, DegenerateTriangleIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.points[3] = {1e-14, 1e-14};  // on the diagonal 0-2: zero area up to round-off
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_inverted, 1);
  EXPECT_EQ(report.first_inverted, 1);
  mesh.points[3] = {0.0, 1e-6};  // a thin but valid sliver
  EXPECT_EQ(check_validity(mesh).num_inverted, 0);
  EXPECT_EQ(check_validity(mesh, 1e-3).num_inverted, 1);
}

TEST(CheckValidity, IndexOutOfRangeIsReportedWithoutCrashing) {
  Mesh mesh = two_triangle_square();
  mesh.triangles[1] = {0, 2, 4};
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_bad_indices, 1);
  EXPECT_NE(joined(report).find("triangle 1 (0, 2, 4)"), std::string::npos) << joined(report);
  EXPECT_THROW(check_indices(mesh), Error);
  EXPECT_NO_THROW(check_indices(two_triangle_square()));
}

TEST(CheckValidity, EdgeSharedByThreeTrianglesIsNonConforming) {
  Mesh mesh = two_triangle_square();
  // A third triangle on edge 0-2, folded over the other two.
  mesh.points.push_back({2.0, -1.0});
  mesh.triangles.push_back({0, 4, 2});
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_nonconforming_edges, 1);
  EXPECT_NE(joined(report).find("edge (0, 2) used by 3 triangles"), std::string::npos)
      << joined(report);
}

TEST(CheckValidity, HangingNodeShowsUpAsMissingBoundaryEdges) {
  // Three triangles: the right one is split at the midpoint 4 of the diagonal, which the left
  // triangle does not know about (a T-junction). Edges 0-4, 4-2 and 2-0 are each used once.
  Mesh mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.triangles = {{0, 1, 4}, {4, 1, 2}, {0, 2, 3}};
  mesh.boundary_edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  mesh.boundary_tags = {0, 0, 0, 0};
  mesh.boundary_names = {"wall"};
  const ValidityReport report = check_validity(mesh);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(report.num_missing_boundary_edges, 3);
}

TEST(CheckValidity, SameDirectionEdgeIsNonConforming) {
  // Two counter-clockwise triangles on the same side of edge 0-1: they overlap.
  Mesh mesh = two_triangle_square();
  mesh.points.push_back({0.5, 0.8});
  mesh.triangles.push_back({0, 1, 4});
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_nonconforming_edges, 1);
  EXPECT_EQ(report.num_inverted, 0);
  EXPECT_NE(joined(report).find("edge (0, 1) used by 2 triangles in the same direction"),
            std::string::npos)
      << joined(report);
}

TEST(CheckValidity, UnusedNodeIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.points.push_back({0.5, 0.5});
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_unused_points, 1);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
  EXPECT_NE(joined(report).find("point 4"), std::string::npos);
}

TEST(CheckValidity, MissingBoundaryEdgeIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.boundary_edges.pop_back();
  mesh.boundary_tags.pop_back();
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_missing_boundary_edges, 1);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
  EXPECT_NE(joined(report).find("edge (3, 0)"), std::string::npos) << joined(report);
}

TEST(CheckValidity, ReversedBoundaryEdgeIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.boundary_edges[2] = {3, 2};
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_reversed_boundary_edges, 1);
  EXPECT_EQ(report.num_missing_boundary_edges, 0);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
}

TEST(CheckValidity, InteriorOrDuplicateBoundaryEdgeIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.boundary_edges.push_back({0, 2});  // the diagonal is interior
  mesh.boundary_edges.push_back({0, 1});  // listed twice
  mesh.boundary_tags.insert(mesh.boundary_tags.end(), {0, 0});
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_extra_boundary_edges, 2);
  EXPECT_EQ(report.problems.size(), 1u) << joined(report);
}

TEST(CheckValidity, BadTagIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.boundary_tags[2] = 4;
  ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_bad_tags, 1);
  EXPECT_NE(joined(report).find("boundary_tags[2] = 4"), std::string::npos) << joined(report);

  mesh.boundary_tags[2] = -1;
  EXPECT_EQ(check_validity(mesh).num_bad_tags, 1);

  mesh = two_triangle_square();
  mesh.boundary_tags.pop_back();
  EXPECT_EQ(check_validity(mesh).num_bad_tags, 1);
  EXPECT_THROW(check_indices(mesh), Error);
}

TEST(CheckValidity, BadNamesAreReported) {
  Mesh mesh = two_triangle_square();
  mesh.boundary_names = {"wall", "wall", "", "domain"};
  EXPECT_EQ(check_validity(mesh).num_bad_names, 3);
}

TEST(CheckValidity, NonFinitePointIsReported) {
  Mesh mesh = two_triangle_square();
  mesh.points[2].x = std::numeric_limits<double>::quiet_NaN();
  const ValidityReport report = check_validity(mesh);
  EXPECT_EQ(report.num_nonfinite_points, 1);
  EXPECT_EQ(report.num_inverted, 2);  // NaN areas fail the area test too
}

TEST(MeshArea, SignedSum) {
  Mesh mesh = two_triangle_square();
  EXPECT_DOUBLE_EQ(mesh_area(mesh), 1.0);
  mesh.triangles[1] = {0, 3, 2};
  EXPECT_DOUBLE_EQ(mesh_area(mesh), 0.0);
}

}  // namespace
}  // namespace meshd
