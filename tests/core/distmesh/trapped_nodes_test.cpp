// remove_trapped_nodes: interior nodes of three triangles go, the mesh stays a valid
// triangulation of the same region with the same boundary, and the caller's fixed nodes stay.
#include "core/distmesh/trapped_nodes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/delaunay/delaunay.h"
#include "core/mesh/boundary.h"

namespace meshd {
namespace {

double area(const MeshCopy& m) {
  double sum = 0.0;
  for (const auto& t : m.triangles)
    sum += 0.5 * cross(m.points[t[1]] - m.points[t[0]], m.points[t[2]] - m.points[t[0]]);
  return sum;
}

// The valence of each node, and whether it ends a boundary half-edge.
std::vector<int> valences(const MeshCopy& m) {
  std::vector<int> valence(m.points.size(), 0);
  for (const auto& t : m.triangles)
    for (int32_t v : t) ++valence[v];
  return valence;
}

std::vector<char> boundary_nodes(const MeshCopy& m) {
  std::vector<char> on(m.points.size(), 0);
  for (const auto& e : half_edge_ends(m.triangles, m.boundary)) on[e[0]] = on[e[1]] = 1;
  return on;
}

MeshCopy copy_of(std::vector<Vec2> points, std::vector<std::array<int32_t, 3>> triangles) {
  MeshCopy m;
  m.points = std::move(points);
  m.triangles = std::move(triangles);
  m.boundary = boundary_half_edges(m.triangles);
  m.below = std::vector<int32_t>{};
  m.tidy = true;
  return m;
}

// A node at the centre of an equilateral triangle, joined to its corners.
MeshCopy lone_star() {
  const double r = std::sqrt(3.0) / 2.0;
  return copy_of({{0.0, 0.0}, {1.0, 0.0}, {0.5, r}, {0.5, r / 3.0}},
                 {{3, 0, 1}, {3, 1, 2}, {3, 2, 0}});
}

TEST(TrappedNodes, ANodeOfThreeTrianglesGivesWayToItsNeighboursTriangle) {
  MeshCopy m = lone_star();
  EXPECT_EQ(remove_trapped_nodes(m, 0), 1);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_GT(cross(m.points[m.triangles[0][1]] - m.points[m.triangles[0][0]],
                  m.points[m.triangles[0][2]] - m.points[m.triangles[0][0]]),
            0.0)
      << "the new triangle turns as the old ones did";
  // All three edges of the new triangle are the boundary, each once, in the new numbering.
  EXPECT_EQ(m.boundary, boundary_half_edges(m.triangles));
  EXPECT_EQ(m.boundary.size(), 3u);
  ASSERT_TRUE(m.below.has_value());
  EXPECT_EQ(*m.below, std::vector<int32_t>{0}) << "the new triangle is measured again";
  EXPECT_FALSE(m.tidy) << "node 3 is no triangle's corner any more";
}

TEST(TrappedNodes, AnEngineThatFoundNoneIsBelieved) {
  MeshCopy m = lone_star();
  m.none_trapped = true;  // as the GPU engine reports it after counting on the device
  const auto before = m.triangles;
  EXPECT_EQ(remove_trapped_nodes(m, 0), 0);
  EXPECT_EQ(m.triangles, before);
}

TEST(TrappedNodes, FixedAndBoundaryNodesStay) {
  MeshCopy fixed = lone_star();
  std::swap(fixed.points[0], fixed.points[3]);  // the centre becomes point 0, fixed
  for (auto& t : fixed.triangles)
    for (int32_t& v : t) v = v == 0 ? 3 : (v == 3 ? 0 : v);
  fixed.boundary = boundary_half_edges(fixed.triangles);
  EXPECT_EQ(remove_trapped_nodes(fixed, 1), 0);
  EXPECT_EQ(fixed.triangles.size(), 3u);
  EXPECT_TRUE(fixed.tidy);

  // Node 1 of a strip of three triangles has three triangles, but lies on the boundary.
  MeshCopy strip =
      copy_of({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}}, {{0, 1, 3}, {1, 4, 3}, {1, 2, 4}});
  EXPECT_EQ(remove_trapped_nodes(strip, 0), 0);
  EXPECT_EQ(strip.triangles.size(), 3u);
}

// Random points' Delaunay triangulations hold many trapped nodes, some next to each other and
// some whose removal traps a neighbour.
TEST(TrappedNodes, RandomTriangulationsLoseEveryTrappedNodeAndKeepTheirRegion) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int all_trapped = 0;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec2> points(400);
    for (Vec2& p : points) p = {unit(rng), unit(rng)};
    MeshCopy m = copy_of(points, delaunay_triangulate(points).triangles);
    const int32_t nfix = 10;
    const std::vector<int> before = valences(m);
    const std::vector<char> on_before = boundary_nodes(m);
    int trapped = 0;
    for (size_t v = nfix; v < points.size(); ++v) trapped += before[v] == 3 && !on_before[v];
    all_trapped += trapped;
    const double area_before = area(m);
    const auto boundary_before = boundary_edges_of(m.triangles);
    const size_t triangles_before = m.triangles.size();
    const std::vector<std::array<int32_t, 3>> original = m.triangles;

    const int64_t removed = remove_trapped_nodes(m, nfix);
    EXPECT_GE(removed, trapped) << trial;
    EXPECT_EQ(m.triangles.size(), triangles_before - 2 * static_cast<size_t>(removed)) << trial;
    EXPECT_NEAR(area(m), area_before, 1e-12) << trial;
    for (const auto& t : m.triangles)
      EXPECT_GT(cross(m.points[t[1]] - m.points[t[0]], m.points[t[2]] - m.points[t[0]]), 0.0);
    EXPECT_EQ(m.boundary, boundary_half_edges(m.triangles)) << trial;
    auto sorted = [](std::vector<std::array<int32_t, 2>> e) {
      std::sort(e.begin(), e.end());
      return e;
    };
    EXPECT_EQ(sorted(boundary_edges_of(m.triangles)), sorted(boundary_before)) << trial;
    const std::vector<int> after = valences(m);
    const std::vector<char> on_after = boundary_nodes(m);
    for (size_t v = 0; v < points.size(); ++v) {
      if (v < static_cast<size_t>(nfix)) {
        EXPECT_GT(after[v], 0) << "fixed node " << v << " was removed";
      }
      EXPECT_FALSE(v >= static_cast<size_t>(nfix) && !on_after[v] && after[v] == 3)
          << "trial " << trial << ": node " << v << " is still trapped";
    }
    // Every triangle a merge made is among those the optimisation measures again.
    ASSERT_TRUE(m.below.has_value());
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      const bool made =
          std::find(original.begin(), original.end(), m.triangles[t]) == original.end();
      if (made) {
        EXPECT_TRUE(std::binary_search(m.below->begin(), m.below->end(), static_cast<int32_t>(t)))
            << "trial " << trial << ": new triangle " << t;
      }
    }
  }
  EXPECT_GT(all_trapped, 20) << "the trials should exercise the removal";
}

}  // namespace
}  // namespace meshd
