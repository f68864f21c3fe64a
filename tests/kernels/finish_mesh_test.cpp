// The finish on the device (finish_mesh.h, GpuEngine::read_mesh and measure_quality) against the
// host's definitions on the same triangles: the boundary that matching edges finds, the triangles
// under the optimisation's threshold, the tidiness that assemble_mesh relies on, and
// summarize_quality's numbers.
#include "kernels/finish_mesh.h"

#include <gtest/gtest.h>

#include <string>

#include "core/common/thread_pool.h"
#include "core/distmesh/assemble_mesh.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/node_estimate.h"
#include "core/distmesh/optimize_worst.h"
#include "core/geometry/compile.h"
#include "core/mesh/boundary.h"
#include "kernels/gpu_engine.h"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

// Random points relaxed for a while on the CPU engine: a mesh with triangles on both sides of
// the threshold, and a boundary.
std::vector<Vec2> part_relaxed(const CompiledProblem& c) {
  ThreadPool pool;
  CpuEngine relax(pool);
  relax.load_points(c, testing::random_points(c, 2000, 7));
  relax.retriangulate(true);
  for (int i = 1; i <= 20; ++i) {
    relax.move_points();
    if (i % 10 == 0) relax.retriangulate(false);
  }
  std::vector<Vec2> pts;
  relax.read_points(pts);
  return pts;
}

void expect_same_quality(const QualityStats& device, const QualityStats& host,
                         const std::string& what) {
  EXPECT_EQ(device.q_min, host.q_min) << what;  // the same radius ratios, bit for bit
  EXPECT_NEAR(device.q_mean, host.q_mean, 1e-12) << what;
  EXPECT_NEAR(device.min_angle_deg, host.min_angle_deg, 1e-9) << what;
  EXPECT_EQ(device.histogram, host.histogram) << what;
}

TEST(GpuFinish, TheDevicesCopyMatchesTheHostsDefinitions) {
  SKIP_WITHOUT_GPU();
  for (const std::string id : {"G1", "G2", "G3", "G4", "G5"}) {
    Problem p = testing::benchmark_problem(id, 0.1);
    p.h0 = h0_for_node_count(p, 2000);
    const CompiledProblem c = compile_problem(p);
    GpuEngine gpu(0);
    gpu.load_points(c, part_relaxed(c));
    gpu.retriangulate(true);
    MeshCopy copy;
    gpu.read_mesh(copy);
    ASSERT_FALSE(copy.triangles.empty()) << id;
    EXPECT_EQ(copy.boundary, boundary_half_edges(copy.triangles)) << id;
    EXPECT_FALSE(copy.boundary.empty()) << id;

    ASSERT_TRUE(copy.below.has_value()) << id;
    std::vector<int32_t> below;
    std::vector<char> used(copy.points.size(), 0);
    bool turned = false;
    for (size_t t = 0; t < copy.triangles.size(); ++t) {
      const auto& v = copy.triangles[t];
      const Vec2 a = copy.points[v[0]], b = copy.points[v[1]], d = copy.points[v[2]];
      if (oriented_radius_ratio(a, b, d) < kOptimizeBelowQuality)
        below.push_back(static_cast<int32_t>(t));
      turned |= cross(b - a, d - a) < 0.0;
      for (int32_t k : v) used[k] = 1;
    }
    EXPECT_EQ(*copy.below, below) << id;
    EXPECT_FALSE(below.empty()) << id << ": the test no longer exercises the threshold";
    const bool all_used = std::find(used.begin(), used.end(), 0) == used.end();
    EXPECT_EQ(copy.tidy, all_used && !turned) << id;

    // Trapped nodes as trapped_nodes.h defines them: fixed ones and boundary ones excluded.
    std::vector<int> valence(copy.points.size(), 0);
    std::vector<char> on_boundary(copy.points.size(), 0);
    for (const auto& v : copy.triangles)
      for (int32_t k : v) ++valence[k];
    for (const auto& e : half_edge_ends(copy.triangles, copy.boundary))
      on_boundary[e[0]] = on_boundary[e[1]] = 1;
    int trapped = 0;
    for (size_t v = c.fixed_points.size(); v < copy.points.size(); ++v)
      trapped += valence[v] == 3 && !on_boundary[v];
    EXPECT_EQ(copy.none_trapped, trapped == 0) << id << ": " << trapped << " trapped";

    // The quality as it stands, then after the optimisation moved nodes.
    Mesh mesh = assemble_mesh(c, copy.points, copy.triangles, copy.boundary, copy.tidy);
    expect_same_quality(gpu.measure_quality(mesh, false), summarize_quality(mesh), id);
    std::vector<Vec2> points = copy.points;
    const int64_t moves =
        optimize_worst_elements(c, points, copy.triangles, copy.boundary, &*copy.below);
    ASSERT_GT(moves, 0) << id;
    mesh = assemble_mesh(c, points, copy.triangles, copy.boundary, copy.tidy);
    expect_same_quality(gpu.measure_quality(mesh, true), summarize_quality(mesh),
                        id + " after the optimisation");
  }
}

}  // namespace
}  // namespace meshd
