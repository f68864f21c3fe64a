// summarize_quality against the plain definitions, on meshes where many triangles tie for the
// smallest angle (the candidates it keeps for atan2 are pruned many times) and where one wins.
#include "core/mesh/quality.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

// Every triangle's radius ratio and smallest angle, in triangle order.
QualityStats brute_force(const Mesh& mesh) {
  QualityStats s;
  s.q_min = std::numeric_limits<double>::infinity();
  s.min_angle_deg = 180.0;
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    const double q = radius_ratio(a, b, c);
    s.q_min = std::min(s.q_min, q);
    sum += q;
    s.min_angle_deg = std::min(s.min_angle_deg, min_angle_deg(a, b, c));
    ++s.histogram[std::clamp(static_cast<int>(q * kQualityBins), 0, kQualityBins - 1)];
  }
  s.q_mean = sum / static_cast<double>(mesh.triangles.size());
  return s;
}

void expect_same(const QualityStats& a, const QualityStats& b) {
  EXPECT_EQ(a.q_min, b.q_min);
  EXPECT_EQ(a.q_mean, b.q_mean);
  EXPECT_EQ(a.min_angle_deg, b.min_angle_deg);
  EXPECT_EQ(a.histogram, b.histogram);
}

TEST(SummarizeQuality, AllTrianglesTieForTheSmallestAngle) {
  const Mesh mesh = testing::structured_square_mesh(40, 30, 4.0, 3.0);  // square cells
  const QualityStats s = summarize_quality(mesh);
  expect_same(s, brute_force(mesh));
  EXPECT_NEAR(s.min_angle_deg, 45.0, 1e-9);
}

TEST(SummarizeQuality, PerturbedMeshMatchesTheDefinitions) {
  Mesh mesh = testing::structured_square_mesh(40, 30);
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    // Interior nodes only, by a deterministic wiggle well under half a cell.
    Vec2& p = mesh.points[i];
    if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0) continue;
    p.x += 0.004 * std::sin(12.9898 * static_cast<double>(i));
    p.y += 0.004 * std::cos(78.233 * static_cast<double>(i));
  }
  expect_same(summarize_quality(mesh), brute_force(mesh));
}

TEST(SummarizeQuality, EmptyMesh) {
  const QualityStats s = summarize_quality(Mesh{});
  EXPECT_EQ(s.q_min, 0.0);
  EXPECT_EQ(s.min_angle_deg, 0.0);
}

}  // namespace
}  // namespace meshd
