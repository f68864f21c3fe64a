// The device's initial triangulation (lattice_triangulation.h) against the host's
// (initial_triangulation.h) on the same kept grid points: the same triangles and links, bit for
// bit, with holes in the lattice, fixed points inside it and pockets along its hull.
#include "kernels/lattice_triangulation.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/distmesh/initial_triangulation.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

Triangulation triangulate_on_device(const InitialGrid& grid, const std::vector<uint8_t>& kept,
                                    const std::vector<Vec2>& p, int64_t nfix) {
  std::vector<int32_t> position(kept.size());
  int32_t sum = 0;
  for (size_t k = 0; k < kept.size(); ++k) {
    position[k] = sum;
    sum += kept[k];
  }
  gpu::DeviceBuffer<uint8_t> d_kept, temp;
  gpu::DeviceBuffer<int32_t> d_position;
  gpu::DeviceBuffer<Vec2> points;
  gpu::DeviceBuffer<gpu::Tri> tris, nbrs;
  gpu::LatticeScratch scratch;
  gpu::GapScratch gaps;
  cudaStream_t stream = nullptr;
  d_kept.upload(kept.data(), kept.size(), stream);
  d_position.upload(position.data(), position.size(), stream);
  points.upload(p.data(), p.size(), stream);
  if (!gpu::lattice_triangulation(grid, d_kept.span(), d_position.span(), nfix, points.span(), tris,
                                  nbrs, scratch, gaps, temp, stream))
    return {};
  return testing::download_triangulation(tris, nbrs, stream);
}

TEST(GpuLatticeTriangulation, TheSameTrianglesAndLinksAsTheHost) {
  SKIP_WITHOUT_GPU();
  for (const std::string id : {"G1", "G2", "G3", "G4", "G5"}) {
    for (uint32_t seed = 0; seed < 3; ++seed) {
      SCOPED_TRACE(id + ", seed " + std::to_string(seed));
      Problem problem = testing::benchmark_problem(id, 0.1);
      problem.h0 = h0_for_node_count(problem, 5000);
      const CompiledProblem c = compile_problem(problem);
      const InitialGrid grid = make_initial_grid(c.bbox, c.h0);
      // The grid points inside the domain, less a random tenth (holes in the lattice) and those
      // right next to a fixed point, as step 2 drops them.
      std::mt19937 rng(seed);
      std::vector<uint8_t> kept(grid.nx * grid.ny, 0);
      std::vector<Vec2> p = c.fixed_points;
      for (size_t k = 0; k < kept.size(); ++k) {
        const Vec2 q = initial_grid_point(grid, static_cast<int64_t>(k));
        bool near_fixed = false;
        for (const Vec2 f : c.fixed_points) near_fixed |= norm(q - f) < 0.5 * c.h0;
        kept[k] = eval_sdf(c.geometry.view(), q) < 0.0 && rng() % 10 != 0 && !near_fixed;
        if (kept[k]) p.push_back(q);
      }
      const Triangulation host = initial_triangulation(grid, kept, c.fixed_points);
      ASSERT_FALSE(host.triangles.empty());
      const auto nfix = static_cast<int64_t>(c.fixed_points.size());
      const Triangulation device = triangulate_on_device(grid, kept, p, nfix);
      ASSERT_FALSE(device.triangles.empty()) << "the device's completion failed";
      EXPECT_EQ(device.triangles, host.triangles);
      EXPECT_EQ(device.neighbors, host.neighbors);
    }
  }
}

}  // namespace
}  // namespace meshd
