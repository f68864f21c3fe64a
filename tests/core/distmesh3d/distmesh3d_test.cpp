#include "core/distmesh3d/distmesh3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/common/error.h"
#include "core/delaunay/flip_repair3.h"
#include "core/distmesh3d/cpu_engine3.h"
#include "core/distmesh3d/geometry_domain3d.h"
#include "core/distmesh3d/surface_offset3d.h"
#include "core/mesh3d/tet_quality.h"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

using testing::csg3;
using testing::cuboid;
using testing::sphere;

double volume(const Relaxed3& r) {
  double v = 0.0;
  for (const auto& t : r.tets) {
    const Vec3 a = r.points[t[0]];
    v += dot(r.points[t[1]] - a, cross(r.points[t[2]] - a, r.points[t[3]] - a)) / 6.0;
  }
  return v;
}

// Every node used, every tetrahedron positive, no node outside, the surface's nodes on the
// boundary within 1e-3 h0.
void expect_valid(const Domain3& domain, const Relaxed3& r, double h0) {
  std::vector<char> used(r.points.size(), 0);
  for (const auto& t : r.tets) {
    for (int32_t v : t) used[v] = 1;
    const Vec3 a = r.points[t[0]];
    EXPECT_GT(dot(r.points[t[1]] - a, cross(r.points[t[2]] - a, r.points[t[3]] - a)), 0.0);
  }
  for (char u : used) EXPECT_TRUE(u);
  for (const Vec3& p : r.points) EXPECT_LT(domain.distance(p), 1e-3 * h0);
  const SurfaceOffset3 off = surface_offset3d(domain, r.points, r.tets, 1e-3 * h0);
  EXPECT_GT(off.surface, 0);
  EXPECT_EQ(off.beyond, 0) << "farthest " << off.max / h0 << " h0";
}

TEST(Distmesh3d, MeshesTheUnitBallWithoutSlivers) {
  GeometryDomain3 ball(sphere({0, 0, 0}, 1.0), 0.2);
  ThreadPool pool(2);
  const Relaxed3 r = distmesh3d(ball.domain(), 0.2, Params3{}, &pool);
  EXPECT_TRUE(r.converged);
  expect_valid(ball.domain(), r, 0.2);
  const TetQualityStats q = summarize_tet_quality(r.points, r.tets);
  EXPECT_GE(q.q_min, 0.2);
  EXPECT_GE(q.q_mean, 0.85);
  EXPECT_GE(q.min_dihedral_deg, 10.0);
  // Chords of a sphere cut into it: about 1% of the volume at 0.2.
  EXPECT_NEAR(volume(r), 4.0 / 3.0 * M_PI, 0.02 * 4.0 / 3.0 * M_PI);
}

TEST(Distmesh3d, ABoxStaysABox) {
  GeometryDomain3 box(
      csg3(CsgOp::kDifference, {cuboid({-1, -1, -1}, {1, 1, 1}), sphere({0, 0, 0}, 0.5)}), 0.25);
  const Relaxed3 r = distmesh3d(box.domain(), 0.25, Params3{}, nullptr);
  expect_valid(box.domain(), r, 0.25);
  // Fixed corners and edges keep the cube's volume but for the hole's chords.
  const double exact = 8.0 - 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_NEAR(volume(r), exact, 0.01 * exact);
  // Every corner is a node of some tetrahedron (expect_valid: every node is used).
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner{i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0};
    bool found = false;
    for (const Vec3& p : r.points) found = found || norm(p - corner) < 1e-12;
    EXPECT_TRUE(found) << "corner " << i;
  }
  const TetQualityStats q = summarize_tet_quality(r.points, r.tets);
  EXPECT_GE(q.q_min, 0.2);
  EXPECT_GE(q.min_dihedral_deg, 10.0);
}

TEST(Distmesh3d, TheSameMeshOnAnyNumberOfThreads) {
  GeometryDomain3 ball(sphere({0, 0, 0}, 1.0), 0.25);
  ThreadPool one(1), three(3);
  const Relaxed3 a = distmesh3d(ball.domain(), 0.25, Params3{}, &one);
  const Relaxed3 b = distmesh3d(ball.domain(), 0.25, Params3{}, &three);
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.tets.size(), b.tets.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_TRUE(a.points[i] == b.points[i]);
  EXPECT_TRUE(a.tets == b.tets);
}

// Asks a snapshot every `every` iterations and keeps what it got.
class SnapshotRecorder : public Observer {
 public:
  explicit SnapshotRecorder(int every) : every_(every) {}
  bool wants_snapshot(int iteration) override { return iteration % every_ == 0; }
  void on_volume_snapshot(int iteration, const std::vector<Vec3>& points,
                          const std::vector<std::array<int32_t, 4>>* tetrahedra) override {
    iterations.push_back(iteration);
    if (tetrahedra != nullptr) tets = *tetrahedra;
    carried.push_back(tetrahedra != nullptr);
    // The tetrahedra held number the nodes of every snapshot since they came.
    int32_t highest = -1;
    for (const auto& t : tets)
      for (int32_t v : t) highest = std::max(highest, v);
    consistent = consistent && !tets.empty() && highest < static_cast<int32_t>(points.size());
  }
  std::vector<int> iterations;
  std::vector<bool> carried;
  std::vector<std::array<int32_t, 4>> tets;
  bool consistent = true;

 private:
  int every_;
};

TEST(Distmesh3d, SnapshotsFollowTheLoopAndChangeNothing) {
  GeometryDomain3 box(
      csg3(CsgOp::kDifference, {cuboid({-1, -1, -1}, {1, 1, 1}), sphere({0, 0, 0}, 0.5)}), 0.25);
  const Relaxed3 plain = distmesh3d(box.domain(), 0.25, Params3{}, nullptr);
  SnapshotRecorder recorder(4);
  const Relaxed3 watched = distmesh3d(box.domain(), 0.25, Params3{}, nullptr, &recorder);
  ASSERT_FALSE(recorder.iterations.empty());
  for (int it : recorder.iterations) EXPECT_EQ(it % 4, 0);
  EXPECT_EQ(recorder.iterations.back(), watched.iterations / 4 * 4);
  EXPECT_TRUE(recorder.carried.front()) << "the first snapshot has no tetrahedra";
  EXPECT_TRUE(recorder.consistent);
  // Only snapshots after a retriangulation carry the tetrahedra again.
  const auto carrying = std::count(recorder.carried.begin(), recorder.carried.end(), true);
  EXPECT_LE(carrying, watched.retriangulations);
  EXPECT_LT(carrying, static_cast<long>(recorder.carried.size()));
  ASSERT_EQ(plain.points.size(), watched.points.size());
  for (size_t i = 0; i < plain.points.size(); ++i)
    EXPECT_TRUE(plain.points[i] == watched.points[i]);
  EXPECT_TRUE(plain.tets == watched.tets);
}

// The CPU engine's steps with the host's repair by flips, as the GPU engine repairs on the
// device: what the loop's repaired retriangulations run on without a GPU.
class RepairingEngine final : public Engine3 {
 public:
  const char* name() const override { return "cpu+flips"; }
  void begin(const Domain3& domain, double h0, const Params3& params) override {
    cpu_.begin(domain, h0, params);
    kept_ = false;
  }
  void start(Nodes3& nodes, const Topology3& topology) override {
    nodes_ = &nodes;
    cpu_.start(nodes, topology);
  }
  StepResult step() override { return cpu_.step(); }
  std::vector<int32_t> crowded_nodes() override { return cpu_.crowded_nodes(); }
  void sync() override {}
  void keep_triangulation(const std::vector<std::array<int32_t, 4>>& all, int64_t nodes) override {
    kept_ = flips_.keep(all, nodes);
    ++kept;
  }
  void forget_triangulation() override { kept_ = false; }
  std::optional<std::vector<std::array<int32_t, 4>>> repair_triangulation() override {
    if (!kept_ || !flips_.repair(nodes_->points).usable()) return std::nullopt;
    return flips_.tets();
  }
  int kept = 0;

 private:
  CpuEngine3 cpu_{nullptr};
  FlipRepair3 flips_;
  Nodes3* nodes_ = nullptr;
  bool kept_ = false;
};

TEST(Distmesh3d, RepairedRetriangulationsServeTheLoop) {
  GeometryDomain3 box(
      csg3(CsgOp::kDifference, {cuboid({-1, -1, -1}, {1, 1, 1}), sphere({0, 0, 0}, 0.5)}), 0.25);
  RepairingEngine engine;
  const Relaxed3 r = distmesh3d(box.domain(), 0.25, Params3{}, nullptr, nullptr, nullptr, &engine);
  EXPECT_GT(r.repaired_retriangulations, 0);
  EXPECT_LE(r.repaired_retriangulations + r.partial_retriangulations, r.retriangulations - 2);
  // The first build was kept for the repairs to start from.
  EXPECT_GE(engine.kept, 1);
  expect_valid(box.domain(), r, 0.25);
  const TetQualityStats q = summarize_tet_quality(r.points, r.tets);
  EXPECT_GE(q.q_min, 0.2);
  EXPECT_GE(q.q_mean, 0.85);
  EXPECT_GE(q.min_dihedral_deg, 10.0);
}

TEST(Distmesh3d, ABadH0IsNamed) {
  GeometryDomain3 ball(sphere({0, 0, 0}, 1.0), 0.25);
  try {
    distmesh3d(ball.domain(), 0.0, Params3{}, nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "h0");
  }
}

}  // namespace
}  // namespace meshd
