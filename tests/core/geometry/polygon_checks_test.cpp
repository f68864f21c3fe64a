#include "core/geometry/polygon_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/common/error.h"

namespace meshd {
namespace {

constexpr const char* kPath = "geometry.polygon";

// The message of the error that check_simple_polygon throws, after checking code and field.
std::string failure(const std::vector<Vec2>& vertices) {
  try {
    check_simple_polygon(vertices, kPath);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "geometry.polygon.vertices");
    return e.detail();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// G3 of geometries.md: a non-convex polygon with 10 vertices.
std::vector<Vec2> g3() {
  return {{-0.4, -0.5}, {0.4, -0.2}, {0.4, -0.7}, {1.5, -0.4}, {0.9, 0.1},
          {1.6, 0.8},   {0.5, 0.5},  {0.2, 1},    {0.1, 0.4},  {-0.7, 0.7}};
}

// n vertices on the unit circle, counter-clockwise.
std::vector<Vec2> circle(int n) {
  std::vector<Vec2> v(n);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    v[i] = {std::cos(a), std::sin(a)};
  }
  return v;
}

// A comb with m unit-wide teeth: many edges cut the sweep line at once.
std::vector<Vec2> comb(int m) {
  std::vector<Vec2> v{{0, -1}};
  for (int i = 0; i < m; ++i) {
    v.insert(v.end(), {{2.0 * i, 1}, {2.0 * i + 1, 1}, {2.0 * i + 1, 0}, {2.0 * i + 2, 0}});
  }
  v.push_back({2.0 * m, -1});
  return v;
}

TEST(PolygonChecks, AcceptsSimplePolygonsInEitherOrientation) {
  std::vector<Vec2> v = g3();
  EXPECT_NO_THROW(check_simple_polygon(v, kPath));
  std::reverse(v.begin(), v.end());
  EXPECT_NO_THROW(check_simple_polygon(v, kPath));
  EXPECT_NO_THROW(check_simple_polygon({{0, 0}, {1, 0}, {0, 1}}, kPath));
  // Collinear neighbours (a vertex in the middle of a side) are fine.
  EXPECT_NO_THROW(check_simple_polygon({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}}, kPath));
  // Vertical edges and a vertex straight above another.
  EXPECT_NO_THROW(check_simple_polygon({{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}, kPath));
}

TEST(PolygonChecks, FewerThanThreeVertices) {
  const std::string message = failure({{0, 0}, {1, 0}});
  EXPECT_NE(message.find("at least 3 vertices (got 2)"), std::string::npos) << message;
}

TEST(PolygonChecks, NonFiniteVertex) {
  const std::string message = failure({{0, 0}, {1, NAN}, {0, 1}});
  EXPECT_NE(message.find("vertex 1"), std::string::npos) << message;
  EXPECT_NE(message.find("not finite"), std::string::npos) << message;
}

TEST(PolygonChecks, FirstVertexRepeatedAtTheEnd) {
  const std::string message = failure({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}});
  EXPECT_NE(message.find("vertices 0 and 4 are the same point (0, 0)"), std::string::npos)
      << message;
  EXPECT_NE(message.find("do not repeat the first vertex"), std::string::npos) << message;
}

TEST(PolygonChecks, RepeatedVertex) {
  const std::string message = failure({{0, 0}, {2, 0}, {1, 1}, {2, 2}, {0, 2}, {1, 1}});
  EXPECT_NE(message.find("vertices 2 and 5 are the same point (1, 1)"), std::string::npos)
      << message;
}

TEST(PolygonChecks, ZeroArea) {
  const std::string message = failure({{0, 0}, {1, 1}, {3, 3}, {2, 2}});
  EXPECT_NE(message.find("zero area"), std::string::npos) << message;
}

TEST(PolygonChecks, EdgeTurningBack) {
  // (2,2) -> (2,3) -> (2,1.5) runs back down the previous edge.
  const std::string message = failure({{0, 0}, {2, 0}, {2, 2}, {2, 3}, {2, 1.5}, {0, 2}});
  EXPECT_NE(message.find("edges 2 and 3 overlap"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 3 (2, 3)"), std::string::npos) << message;
}

TEST(PolygonChecks, Bowtie) {
  const std::string message = failure({{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  EXPECT_NE(message.find("edges 0 and 2 cross near (0.5, 0.5)"), std::string::npos) << message;
}

TEST(PolygonChecks, NamesTheCrossingEdges) {
  // Vertex 6 moved below edge 2: edge 6, on its way back up to vertex 7, cuts through edge 2.
  std::vector<Vec2> v = g3();
  v[6] = {1.5, -0.8};
  const std::string message = failure(v);
  EXPECT_NE(message.find("edges 2 and 6 cross near ("), std::string::npos) << message;
  EXPECT_NE(message.find("edge i joins vertices i and i+1"), std::string::npos) << message;
}

TEST(PolygonChecks, VertexOnAnotherEdge) {
  // Vertex 3 (2,0) lies on edge 0.
  const std::string message = failure({{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}});
  EXPECT_NE(message.find("edges 0 and "), std::string::npos) << message;
  EXPECT_NE(message.find("touch at (2, 0)"), std::string::npos) << message;
}

TEST(PolygonChecks, CollinearOverlapOfDistantEdges) {
  // A slot whose two walls share the line x = 1 over [1, 2]: edges 1 and 5 overlap.
  const std::string message =
      failure({{0, 0}, {1, 0}, {1, 2}, {3, 2}, {3, 3}, {1, 3}, {1, 1}, {0, 1}});
  EXPECT_NE(message.find(" touch at "), std::string::npos) << message;
}

TEST(PolygonChecks, LargePolygonsAreFast) {
  // 100,000 vertices each; a quadratic check would take minutes.
  EXPECT_NO_THROW(check_simple_polygon(circle(100'000), kPath));
  EXPECT_NO_THROW(check_simple_polygon(comb(25'000), kPath));

  // Swapping two neighbours makes the edges before and after them cross.
  std::vector<Vec2> v = circle(100'000);
  std::swap(v[50'000], v[50'001]);
  const std::string message = failure(v);
  EXPECT_NE(message.find("edges 49999 and 50001 cross"), std::string::npos) << message;

  // Tooth 15000's top-left corner pulled over its own right wall.
  std::vector<Vec2> c = comb(25'000);
  c[60'001] = {30'003, 2};
  const std::string comb_message = failure(c);
  EXPECT_NE(comb_message.find("edges 60000 and 60002 cross"), std::string::npos) << comb_message;
}

// The same definition checked pair by pair: the reference for the sweep.
bool simple_by_brute_force(const std::vector<Vec2>& v) {
  const int n = static_cast<int>(v.size());
  auto orient = [](Vec2 a, Vec2 b, Vec2 c) {
    const double o = cross(b - a, c - a);  // exact on small integers
    return (o > 0) - (o < 0);
  };
  auto on = [&](Vec2 a, Vec2 b, Vec2 p) {
    return orient(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
           std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
  };
  bool collinear = true;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j)
      if (v[i] == v[j]) return false;
    collinear = collinear && orient(v[0], v[1], v[i]) == 0;
  }
  if (collinear) return false;
  for (int i = 0; i < n; ++i) {
    const Vec2 a = v[(i + n - 1) % n], b = v[i], c = v[(i + 1) % n];
    if (orient(a, b, c) == 0 && dot(b - a, c - b) < 0) return false;
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours
      const Vec2 a = v[i], b = v[(i + 1) % n], c = v[j], d = v[(j + 1) % n];
      if (orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0)
        return false;
      if (on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b)) return false;
    }
  }
  return true;
}

TEST(PolygonChecks, AgreesWithBruteForceOnDegenerateRandomPolygons) {
  // Vertices on a small integer grid: collinear edges, vertical edges and touching vertices
  // are common, which is where a sweep goes wrong.
  std::mt19937 rng(12345);
  int simple = 0;
  for (int trial = 0; trial < 50'000; ++trial) {
    const int n = std::uniform_int_distribution<int>(3, 9)(rng);
    const int grid = std::uniform_int_distribution<int>(2, 6)(rng);
    std::uniform_int_distribution<int> coordinate(0, grid);
    std::vector<Vec2> v(n);
    for (Vec2& p : v) p = {double(coordinate(rng)), double(coordinate(rng))};
    const bool expected = simple_by_brute_force(v);
    simple += expected;
    bool accepted = true;
    try {
      check_simple_polygon(v, kPath);
    } catch (const Error&) {
      accepted = false;
    }
    if (accepted != expected) {
      std::string text;
      for (Vec2 p : v) text += "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") ";
      FAIL() << "sweep says " << accepted << ", brute force " << expected << " for " << text;
    }
  }
  EXPECT_GT(simple, 1000);  // the sample holds enough simple polygons to mean something
}

}  // namespace
}  // namespace meshd
