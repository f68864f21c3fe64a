// The device's completion (complete_gaps.h) against the host's (complete_triangulation.h,
// refill_folds.h) on the same partial triangulations: the same triangles and links, bit for bit,
// since both hand CGAL the same gap points and walls in the same order.
#include "kernels/complete_gaps.h"

#include <gtest/gtest.h>

#include <random>

#include "core/delaunay/complete_triangulation.h"
#include "core/delaunay/refill_folds.h"
#include "kernels/gpu_engine.h"
#include "tests/core/delaunay/fold_fixtures.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

using testing::jittered_lattice;
using testing::push_across;

// `tri` without the triangles whose centroid lies within `radius` of `center` or within `margin`
// of the lattice's left side: a hole and pockets along the hull.
Triangulation with_gaps(const std::vector<Vec2>& p, const Triangulation& tri, Vec2 center,
                        double radius, double margin) {
  std::vector<char> drop(tri.triangles.size(), 0);
  for (size_t t = 0; t < tri.triangles.size(); ++t) {
    const auto& v = tri.triangles[t];
    const Vec2 c = (1.0 / 3.0) * (p[v[0]] + p[v[1]] + p[v[2]]);
    drop[t] = norm(c - center) < radius || c.x < margin;
  }
  Triangulation out = tri;
  drop_triangles(out, drop);
  return out;
}

// Runs the device's fold cut and completion on `partial`; returns the result, or nothing when the
// completion failed.
Triangulation complete_on_device(const std::vector<Vec2>& p, const Triangulation& partial,
                                 int64_t nfix) {
  gpu::DeviceBuffer<Vec2> points;
  gpu::DeviceBuffer<gpu::Tri> tris, nbrs;
  gpu::GapScratch scratch;
  gpu::DeviceBuffer<uint8_t> temp;
  cudaStream_t stream = nullptr;
  points.upload(p.data(), p.size(), stream);
  tris.upload(reinterpret_cast<const gpu::Tri*>(partial.triangles.data()), partial.triangles.size(),
              stream);
  nbrs.upload(reinterpret_cast<const gpu::Tri*>(partial.neighbors.data()), partial.neighbors.size(),
              stream);
  gpu::cut_folds(points.span(), tris, nbrs, scratch, temp, stream);
  if (!gpu::complete_gaps(points.span(), nfix, tris, nbrs, scratch, temp, stream)) return {};
  return testing::download_triangulation(tris, nbrs, stream);
}

TEST(GpuCompleteGaps, AHoleAndHullPocketsFillAsOnTheHost) {
  SKIP_WITHOUT_GPU();
  for (uint32_t seed = 0; seed < 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<Vec2> p = jittered_lattice(60, seed);
    const Triangulation partial =
        with_gaps(p, delaunay_triangulate(p), {30.0, 25.0}, 6.0 + seed, 1.5);
    const Triangulation host = complete_triangulation(p, partial, 3);
    ASSERT_FALSE(host.triangles.empty());
    const Triangulation device = complete_on_device(p, partial, 3);
    ASSERT_FALSE(device.triangles.empty()) << "the device's completion failed";
    EXPECT_EQ(device.triangles, host.triangles);
    EXPECT_EQ(device.neighbors, host.neighbors);
  }
}

// Nodes pushed across edges (folds, some next to each other and one by the hull): the device cuts
// them out and fills the holes as refill_folds does.
TEST(GpuCompleteGaps, FoldsCutAndFilledAsOnTheHost) {
  SKIP_WITHOUT_GPU();
  for (uint32_t seed = 0; seed < 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::vector<Vec2> p = jittered_lattice(40, seed);
    const Triangulation before = delaunay_triangulate(p);
    std::mt19937 rng(seed);
    for (int i = 0; i < 8; ++i) push_across(before, static_cast<int32_t>(rng() % p.size()), p);
    push_across(before, 1 * 40 + 20, p);
    const Triangulation host = refill_folds(p, before, 0);
    ASSERT_FALSE(host.triangles.empty()) << "no fold, or the host's fill failed";
    const Triangulation device = complete_on_device(p, before, 0);
    ASSERT_FALSE(device.triangles.empty()) << "the device's fill failed";
    EXPECT_EQ(device.triangles, host.triangles);
    EXPECT_EQ(device.neighbors, host.neighbors);
  }
}

}  // namespace
}  // namespace meshd
