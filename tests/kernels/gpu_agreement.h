// What the GPU-vs-CPU agreement tests share: the skip where no GPU is visible, random points to
// start from, the gaps between their points after a step, the whole-mesh comparison of the two
// engines, and a triangulation read back from the device.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <vector>

#include "core/delaunay/delaunay.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/engine.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/validity.h"
#include "kernels/device_buffer.h"
#include "kernels/gpu_engine.h"
#include "kernels/launch.h"

#define SKIP_WITHOUT_GPU() \
  if (meshd::gpu_device_count() == 0) GTEST_SKIP() << "no CUDA device visible: GPU tests skipped"

namespace meshd::testing {

// Random points inside the domain, fixed points first.
inline std::vector<Vec2> random_points(const CompiledProblem& c, size_t count, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(c.bbox.min.x, c.bbox.max.x),
      uy(c.bbox.min.y, c.bbox.max.y);
  std::vector<Vec2> pts = c.fixed_points;
  while (pts.size() < count) {
    const Vec2 q{ux(rng), uy(rng)};
    if (eval_sdf(c.geometry.view(), q) < 0.0) pts.push_back(q);
  }
  return pts;
}

// Loads `pts` into each engine and triangulates them from scratch.
inline void load_and_triangulate(const CompiledProblem& c, const std::vector<Vec2>& pts,
                                 std::initializer_list<Engine*> engines) {
  for (Engine* e : engines) {
    e->load_points(c, pts);
    e->retriangulate(true);
  }
}

// How far the GPU engine's points `b` lie from the CPU engine's `a` (#N by 2 each) after the same
// step: the largest gap among interior nodes, which agree to rounding, and among nodes within
// 1e-3 h0 of the boundary (projected), which agree to what the finite-difference gradient
// amplifies: one-ulp differences in a position (the L0 scale is a sum in another order) change
// fd by ~1e-16, which the step deps = 1.5e-8 h0 amplifies.
struct PointGaps {
  double interior = 0.0;
  double boundary = 0.0;
};
inline PointGaps point_gaps(const CompiledProblem& c, const std::vector<Vec2>& a,
                            const std::vector<Vec2>& b) {
  PointGaps g;
  for (size_t i = 0; i < a.size(); ++i) {
    const bool projected = std::fabs(eval_sdf(c.geometry.view(), a[i])) < 1e-3 * c.h0;
    double& worst = projected ? g.boundary : g.interior;
    worst = std::max(worst, norm(a[i] - b[i]));
  }
  return g;
}

// The GPU's mesh `rg` against the CPU engine's `rc` of the same problem: valid, as many nodes
// within 2%, q_mean within 0.01, q_min at most 0.05 lower, the area within 0.5%, converged.
inline void expect_meshes_agree(const MeshResult& rc, const MeshResult& rg) {
  const auto validity = check_validity(rg.mesh);
  EXPECT_TRUE(validity.problems.empty()) << validity.problems.front();
  EXPECT_NEAR(static_cast<double>(rg.mesh.points.size()),
              static_cast<double>(rc.mesh.points.size()), 0.02 * rc.mesh.points.size());
  EXPECT_NEAR(rg.quality.q_mean, rc.quality.q_mean, 0.01);
  EXPECT_GE(rg.quality.q_min, rc.quality.q_min - 0.05);
  EXPECT_NEAR(mesh_area(rg.mesh), mesh_area(rc.mesh), 0.005 * mesh_area(rc.mesh));
  EXPECT_TRUE(rg.stats.converged);
}

// The device's triangles and their links, as the host's Triangulation (the same layout).
inline Triangulation download_triangulation(const gpu::DeviceBuffer<gpu::Tri>& tris,
                                            const gpu::DeviceBuffer<gpu::Tri>& nbrs,
                                            cudaStream_t stream) {
  Triangulation out;
  out.triangles.resize(tris.size());
  out.neighbors.resize(nbrs.size());
  tris.download(reinterpret_cast<gpu::Tri*>(out.triangles.data()), stream);
  nbrs.download(reinterpret_cast<gpu::Tri*>(out.neighbors.data()), stream);
  EXPECT_EQ(cudaStreamSynchronize(stream), cudaSuccess);
  return out;
}

}  // namespace meshd::testing
