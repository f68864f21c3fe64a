#include "core/distmesh/spatial_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace meshd {
namespace {

// A 64 x 64 grid shuffled: along the Hilbert curve every node's successor is a grid neighbour.
TEST(HilbertOrder, WalksAShuffledGridOneNeighbourAtATime) {
  std::vector<Vec2> points;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) points.push_back({10.0 + 0.5 * i, -3.0 + 0.5 * j});
  std::shuffle(points.begin(), points.end(), std::mt19937(7));
  std::vector<std::array<int32_t, 3>> no_triangles;
  hilbert_order(points, 0, no_triangles);
  ASSERT_EQ(points.size(), 64u * 64u);
  for (size_t k = 1; k < points.size(); ++k)
    ASSERT_DOUBLE_EQ(norm(points[k] - points[k - 1]), 0.5) << "between " << k - 1 << " and " << k;
}

// The fixed nodes keep their indices, the free ones are only renumbered, and every triangle
// still joins the same three positions in the same turning order.
TEST(HilbertOrder, KeepsFixedNodesFirstAndTrianglesOnTheirPositions) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec2> points;
  for (int i = 0; i < 500; ++i) points.push_back({u(rng), u(rng)});
  std::vector<std::array<int32_t, 3>> triangles;
  for (int k = 0; k < 300; ++k)
    triangles.push_back({static_cast<int32_t>(rng() % 500), static_cast<int32_t>(rng() % 500),
                         static_cast<int32_t>(rng() % 500)});
  const auto before_points = points;
  const auto before_triangles = triangles;
  constexpr int32_t kFixed = 20;
  hilbert_order(points, kFixed, triangles);

  ASSERT_EQ(points.size(), before_points.size());
  for (int32_t i = 0; i < kFixed; ++i) EXPECT_EQ(points[i], before_points[i]);
  auto key = [](Vec2 p) { return std::pair{p.x, p.y}; };
  std::vector<std::pair<double, double>> a, b;
  for (Vec2 p : points) a.push_back(key(p));
  for (Vec2 p : before_points) b.push_back(key(p));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  ASSERT_EQ(triangles.size(), before_triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(points[triangles[t][k]], before_points[before_triangles[t][k]]);
}

}  // namespace
}  // namespace meshd
