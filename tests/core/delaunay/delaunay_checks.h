// Checks of a 2D Delaunay triangulation against delaunay.h's contract by exact predicates, and
// comparisons of triangle sets: shared by the host's and the device's builder tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "core/delaunay/delaunay.h"
#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/parallel_insertion.h"

namespace meshd::testing {

using Triple = std::array<int32_t, 3>;

// A triangle's corners rotated so that the smallest comes first (orientation kept).
inline Triple canonical(Triple t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

inline std::set<Triple> triangle_set(const Triangulation& t) {
  std::set<Triple> out;
  for (const Triple& v : t.triangles) out.insert(canonical(v));
  return out;
}

// The same with each corner named by the first of the points equal to it: CGAL keeps another
// one of a set of duplicates.
inline std::set<Triple> triangle_set_by_position(const std::vector<Vec2>& p,
                                                 const Triangulation& t) {
  std::map<std::pair<double, double>, int32_t> first;
  for (size_t i = 0; i < p.size(); ++i) first.emplace(std::pair{p[i].x, p[i].y}, i);
  std::set<Triple> out;
  for (Triple v : t.triangles) {
    for (int32_t& i : v) i = first.at({p[i].x, p[i].y});
    out.insert(canonical(v));
  }
  return out;
}

// Checks what delaunay.h promises, by exact predicates: every triangle counter-clockwise, links
// mutual, 2 N - 2 - H triangles for N distinct points and H hull edges, every distinct point in a
// triangle, no hull edge turning right, and every interior edge locally Delaunay.
inline void expect_delaunay(const std::vector<Vec2>& p, const Triangulation& t) {
  const std::vector<int32_t> kept = distinct_points(p);
  const auto m = static_cast<int64_t>(t.triangles.size());
  ASSERT_EQ(t.neighbors.size(), t.triangles.size());
  std::vector<char> used(p.size(), 0);
  int64_t hull = 0;
  std::map<int32_t, int32_t> hull_next;  // hull edge a -> b
  for (int64_t x = 0; x < m; ++x) {
    const Triple& v = t.triangles[x];
    ASSERT_GT(orientation_sign(p[v[0]], p[v[1]], p[v[2]]), 0) << "triangle " << x;
    for (int k = 0; k < 3; ++k) {
      used[v[k]] = 1;
      const int32_t a = v[(k + 1) % 3], b = v[(k + 2) % 3];
      const int32_t y = t.neighbors[x][k];
      if (y < 0) {
        ++hull;
        hull_next[a] = b;
        continue;
      }
      const Triple& w = t.triangles[y];
      int back = -1;
      for (int j = 0; j < 3; ++j)
        if (t.neighbors[y][j] == x) back = j;
      ASSERT_GE(back, 0) << "link " << x << " -> " << y << " not mutual";
      ASSERT_EQ(w[(back + 1) % 3], b);
      ASSERT_EQ(w[(back + 2) % 3], a);
      ASSERT_LE(in_circle_sign(p[v[0]], p[v[1]], p[v[2]], p[w[back]]), 0)
          << "edge " << a << "-" << b << " not locally Delaunay";
    }
  }
  // Each distinct position in exactly one of its points' triangles (which of a set of
  // duplicates the builder keeps is its own choice).
  std::map<std::pair<double, double>, int> used_at;
  for (size_t i = 0; i < p.size(); ++i) used_at[{p[i].x, p[i].y}] += used[i];
  for (const auto& [where, count] : used_at)
    EXPECT_EQ(count, 1) << "point (" << where.first << ", " << where.second << ") used " << count;
  EXPECT_EQ(m, 2 * static_cast<int64_t>(kept.size()) - 2 - hull);
  for (const auto& [a, b] : hull_next) {
    ASSERT_TRUE(hull_next.count(b));
    EXPECT_GE(orientation_sign(p[a], p[b], p[hull_next[b]]), 0) << "hull turns right at " << b;
  }
}

inline std::vector<Vec2> uniform_points(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> p(n);
  for (Vec2& q : p) q = {u(rng), u(rng)};
  return p;
}

// `clusters` Gaussian clusters of `each` points, spread from 1 down to 2^-19 of their distance.
inline std::vector<Vec2> clustered_points(int clusters, int each, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec2> p;
  for (int c = 0; c < clusters; ++c) {
    const Vec2 centre{10.0 * g(rng), 10.0 * g(rng)};
    const double spread = std::ldexp(1.0, -static_cast<int>(rng() % 20));
    for (int k = 0; k < each; ++k)
      p.push_back({centre.x + spread * g(rng), centre.y + spread * g(rng)});
  }
  return p;
}

}  // namespace meshd::testing
