#include "core/mesh/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshd {

double min_angle_deg(Vec2 a, Vec2 b, Vec2 c) {
  auto angle = [](Vec2 apex, Vec2 u, Vec2 v) {
    return std::atan2(std::fabs(cross(u - apex, v - apex)), dot(u - apex, v - apex));
  };
  const double m = std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
  return m * 180.0 / M_PI;
}

std::vector<double> triangle_quality(const Mesh& mesh) {
  std::vector<double> q(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    q[i] = radius_ratio(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
  }
  return q;
}

QualityStats summarize_quality(const Mesh& mesh) {
  QualityStats s;
  if (mesh.triangles.empty()) return s;
  s.q_min = std::numeric_limits<double>::infinity();
  s.min_angle_deg = 180.0;
  double sum = 0.0;
  // The smallest angle of a triangle lies between its two longest sides, so its sine is twice
  // the area over their product: a cheap key that orders triangles by smallest angle up to
  // rounding. Three atan2 per triangle are then needed only near the smallest key.
  std::vector<double> sine(mesh.triangles.size());
  double min_sine = INFINITY;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    const double q = radius_ratio(a, b, c);
    s.q_min = std::min(s.q_min, q);
    sum += q;
    const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
    const double shortest = std::min({la, lb, lc});
    const double longest_two = la * lb * lc / shortest;
    sine[i] = shortest > 0.0 ? std::fabs(cross(b - a, c - a)) / longest_two : 0.0;
    min_sine = std::min(min_sine, sine[i]);
    const int bin = std::clamp(static_cast<int>(q * kQualityBins), 0, kQualityBins - 1);
    ++s.histogram[bin];
  }
  const double near = min_sine * (1.0 + 1e-6) + 1e-300;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (sine[i] > near) continue;
    const auto& t = mesh.triangles[i];
    s.min_angle_deg = std::min(
        s.min_angle_deg, min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]));
  }
  s.q_mean = sum / static_cast<double>(mesh.triangles.size());
  return s;
}

}  // namespace meshd
