// The device's repair by flips (kernels/flip_repair3.h) against the host's (the same rounds,
// core/delaunay/flip_repair3.h): the same outcome and the same tetrahedra in the same slots,
// for random points moved a little (a clean repair, CGAL's tetrahedra) and a lot (tetrahedra
// left turned, faces made twice), and for a lattice's cospherical points.
#include "kernels/flip_repair3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/delaunay/delaunay3d.h"
#include "kernels/gpu_engine.h"
#include "tests/core/random_points3.h"

namespace meshd {
namespace {

#define SKIP_WITHOUT_GPU() \
  if (gpu_device_count() == 0) GTEST_SKIP() << "no CUDA device visible: GPU tests skipped"

using Tets = std::vector<std::array<int32_t, 4>>;

void expect_same_repair(const std::vector<Vec3>& before, const std::vector<Vec3>& after) {
  const Tets start = delaunay_tetrahedralize(before, 4);
  const auto n = static_cast<int64_t>(before.size());
  FlipRepair3 host;
  ASSERT_TRUE(host.keep(start, n));
  const RepairOutcome3 h = host.repair(after);
  gpu::KeptTetrahedra3 device;
  ASSERT_TRUE(device.keep(start, n, nullptr));
  gpu::DeviceBuffer<Vec3> p;
  p.upload(after.data(), after.size(), nullptr);
  const RepairOutcome3 d = device.repair(p.span(), kRepairRounds3, nullptr);
  EXPECT_EQ(d.ended, h.ended);
  EXPECT_EQ(d.rounds, h.rounds);
  EXPECT_EQ(d.flips, h.flips);
  EXPECT_EQ(d.inverted, h.inverted);
  EXPECT_EQ(d.stuck, h.stuck);
  EXPECT_EQ(d.overfull, h.overfull);
  EXPECT_GT(d.flips, 0);
  EXPECT_TRUE(device.download(nullptr) == host.tets());
}

TEST(GpuFlipRepair3, RepairsRandomPointsAsTheHostDoes) {
  SKIP_WITHOUT_GPU();
  const size_t n = 50000;
  const std::vector<Vec3> before = testing::random_points3(n, 5);
  const double spacing = 2.0 / std::cbrt(static_cast<double>(n));
  expect_same_repair(before, testing::moved_inner3(before, 0.001 * spacing, 6));
  expect_same_repair(before, testing::moved_inner3(before, 0.2 * spacing, 7));
}

TEST(GpuFlipRepair3, RepairsALatticeAsTheHostDoes) {
  SKIP_WITHOUT_GPU();
  std::vector<Vec3> before;
  for (int i = 0; i <= 24; ++i)
    for (int j = 0; j <= 24; ++j)
      for (int k = 0; k <= 24; ++k)
        before.push_back({i / 12.0 - 1.0, j / 12.0 - 1.0, k / 12.0 - 1.0});
  expect_same_repair(before, testing::moved_inner3(before, 0.001, 3));
}

}  // namespace
}  // namespace meshd
