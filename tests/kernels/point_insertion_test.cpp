// The device's Delaunay builder (kernels/point_insertion.h, through GpuEngine::delaunay, as the
// engine's full triangulations use it) against CGAL: the same triangles where the Delaunay
// triangulation is unique; valid and locally Delaunay under exact predicates everywhere (grids
// of co-circular points, a lattice, clusters, duplicates, far-off coordinates, four million
// points);
// and the same triangles as the host's run of the same steps.
#include "kernels/point_insertion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/gpu_engine.h"
#include "tests/core/delaunay/delaunay_checks.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

using testing::clustered_points;
using testing::expect_delaunay;
using testing::triangle_set;
using testing::triangle_set_by_position;
using testing::uniform_points;

TEST(GpuPointInsertion, SameTrianglesAsCgalAndTheHostInGeneralPosition) {
  SKIP_WITHOUT_GPU();
  GpuEngine engine;
  for (int n : {3, 10, 1000, 50000}) {
    const std::vector<Vec2> p = uniform_points(n, 17);
    GpuEngine::DelaunayTiming timing;
    const Triangulation t = engine.delaunay(p, &timing);
    expect_delaunay(p, t);
    EXPECT_EQ(triangle_set(t), triangle_set(delaunay_triangulate(p))) << n;
    EXPECT_EQ(triangle_set(t), triangle_set(insertion_triangulate(p))) << n;
    if (n >= 1000) {
      EXPECT_GT(timing.insertion_steps, 5);
    }
  }
}

TEST(GpuPointInsertion, CoCircularGridsAndALattice) {
  SKIP_WITHOUT_GPU();
  GpuEngine engine;
  for (int side : {2, 9, 300}) {
    std::vector<Vec2> p;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) p.push_back({0.5 * i, 0.5 * j});
    std::shuffle(p.begin(), p.end(), std::mt19937(side));
    const Triangulation t = engine.delaunay(p);
    expect_delaunay(p, t);
    EXPECT_EQ(static_cast<int64_t>(t.triangles.size()), 2 * int64_t{side - 1} * (side - 1));
  }
  std::vector<Vec2> lattice;
  for (int r = 0; r < 200; ++r)
    for (int i = 0; i < 200; ++i) lattice.push_back({i + 0.5 * (r % 2), r * std::sqrt(3.0) / 2});
  expect_delaunay(lattice, engine.delaunay(lattice));
}

TEST(GpuPointInsertion, ClustersDuplicatesAndFarOffCoordinates) {
  SKIP_WITHOUT_GPU();
  GpuEngine engine;
  const std::vector<Vec2> clusters = clustered_points(50, 400, 3);
  const Triangulation tc = engine.delaunay(clusters);
  expect_delaunay(clusters, tc);
  EXPECT_EQ(triangle_set(tc), triangle_set(delaunay_triangulate(clusters)));

  std::mt19937 rng(4);
  std::vector<Vec2> dup = uniform_points(5000, 5);
  for (int k = 0; k < 1000; ++k) dup.push_back(dup[rng() % 5000]);
  std::shuffle(dup.begin(), dup.end(), rng);
  const Triangulation td = engine.delaunay(dup);
  expect_delaunay(dup, td);
  EXPECT_EQ(triangle_set_by_position(dup, td),
            triangle_set_by_position(dup, delaunay_triangulate(dup)));

  std::vector<Vec2> far = uniform_points(20000, 9);
  for (Vec2& q : far) q = {512000.0 + 3000.0 * q.x, 6663000.0 + 3000.0 * q.y};
  const Triangulation tf = engine.delaunay(far);
  expect_delaunay(far, tf);
  EXPECT_EQ(triangle_set(tf), triangle_set(delaunay_triangulate(far)));
}

// The huge set: four million points, compared as sorted arrays (a std::set of eight
// million triangles would take longer than both builders).
TEST(GpuPointInsertion, FourMillionPoints) {
  SKIP_WITHOUT_GPU();
  GpuEngine engine;
  const std::vector<Vec2> p = uniform_points(4000000, 23);
  const auto sorted = [](const Triangulation& t) {
    std::vector<testing::Triple> v;
    v.reserve(t.triangles.size());
    for (const testing::Triple& x : t.triangles) v.push_back(testing::canonical(x));
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<testing::Triple> device = sorted(engine.delaunay(p));
  // 2 N - 2 - H triangles, with a few dozen hull edges for uniform points.
  EXPECT_GE(device.size(), 2 * p.size() - 200);
  EXPECT_TRUE(device == sorted(delaunay_triangulate(p)));
}

}  // namespace
}  // namespace meshd
