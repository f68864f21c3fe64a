// The CPU engine's steps on tiny configurations, against a direct transcription of
// distmesh2d.m's steps 3-8: the centroid filter and bars, the forces and the projection, density
// control, and bitwise determinism across thread counts.
#include "core/distmesh/cpu_engine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/delaunay/delaunay.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

using Tri = std::array<int32_t, 3>;
using Bar = std::array<int32_t, 2>;

// A compressed configuration: 9 grid points packed in the middle of the unit disk (the box
// limits the grid to [-h0, h0]^2) and fixed nodes on the circle, two of them 0.001 apart.
Problem cluster_problem() {
  Problem p;
  p.geometry = Shape{Circle{{0, 0}, 1}, "outer", ""};
  p.h0 = 0.125;
  p.bbox = Box{{-0.125, -0.125}, {0.125, 0.125}};
  for (int k = 0; k < 8; ++k)
    p.fixed_points.push_back({std::cos(k * M_PI / 4), std::sin(k * M_PI / 4)});
  p.fixed_points.push_back({std::cos(0.001), std::sin(0.001)});
  return p;
}

std::set<Tri> canonical(const std::vector<Tri>& tris) {
  std::set<Tri> out;
  for (Tri t : tris) {
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

std::vector<Bar> unique_edges(const std::vector<Tri>& tris) {
  std::set<Bar> edges;
  for (const Tri& t : tris) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return {edges.begin(), edges.end()};
}

// Steps 4, 5, 7, 8 of distmesh2d.m for the bars of `tris`, written as in the paper.
// projected[i] says whether node i left the domain and was projected back.
std::vector<Vec2> reference_step(const CompiledProblem& c, const std::vector<Vec2>& p,
                                 const std::vector<Tri>& tris, double* max_move,
                                 std::vector<char>* projected, std::vector<double>* unit) {
  const auto bars = unique_edges(tris);
  const double h0 = c.h0, geps = c.params.geps * h0, deps = c.params.deps * h0;
  std::vector<double> L(bars.size()), hbars(bars.size());
  double sum_l2 = 0, sum_h2 = 0;
  for (size_t b = 0; b < bars.size(); ++b) {
    const Vec2 a = p[bars[b][0]], e = p[bars[b][1]];
    L[b] = norm(a - e);
    hbars[b] = eval_size(c.size.view(), 0.5 * (a + e));
    sum_l2 += L[b] * L[b];
    sum_h2 += hbars[b] * hbars[b];
  }
  std::vector<Vec2> ftot(p.size());
  // Moves are measured in each node's own size: h0 times the mean h of its bars.
  std::vector<double> size_sum(p.size(), 0.0), degree(p.size(), 0.0);
  for (size_t b = 0; b < bars.size(); ++b) {
    for (int32_t v : bars[b]) {
      size_sum[v] += hbars[b];
      degree[v] += 1;
    }
  }
  unit->resize(p.size());
  for (size_t i = 0; i < p.size(); ++i)
    (*unit)[i] = degree[i] > 0 ? h0 * size_sum[i] / degree[i] : h0;
  for (size_t b = 0; b < bars.size(); ++b) {
    const double L0 = hbars[b] * c.params.fscale * std::sqrt(sum_l2 / sum_h2);
    const double F = std::max(L0 - L[b], 0.0);
    const Vec2 fvec = (F / L[b]) * (p[bars[b][0]] - p[bars[b][1]]);
    ftot[bars[b][0]] = ftot[bars[b][0]] + fvec;
    ftot[bars[b][1]] = ftot[bars[b][1]] - fvec;
  }
  std::vector<Vec2> q = p;
  *max_move = 0;
  projected->assign(p.size(), 0);
  for (size_t i = c.fixed_points.size(); i < p.size(); ++i) {
    const Vec2 step = c.params.deltat * ftot[i];
    q[i] = p[i] + step;
    const double d = eval_sdf(c.geometry.view(), q[i]);
    if (d > 0) {
      (*projected)[i] = 1;
      const double gx = (eval_sdf(c.geometry.view(), {q[i].x + deps, q[i].y}) - d) / deps;
      const double gy = (eval_sdf(c.geometry.view(), {q[i].x, q[i].y + deps}) - d) / deps;
      q[i] = q[i] - (d / (gx * gx + gy * gy)) * Vec2{gx, gy};
    }
    if (d < -geps) *max_move = std::max(*max_move, norm(step) / (*unit)[i]);
  }
  return q;
}

struct Snapshot {
  std::vector<Vec2> points;
  std::vector<Tri> triangles;
};

Snapshot read(CpuEngine& engine) {
  Snapshot s;
  engine.read_points(s.points);
  engine.read_triangles(s.triangles);
  return s;
}

// ---- Step 3 -------------------------------------------------------------------------------------

void expect_filtered_delaunay(const Problem& problem, bool drops_some) {
  const CompiledProblem c = compile_problem(problem);
  ThreadPool pool(2);
  CpuEngine engine(pool);
  const int64_t n = engine.initialize(c);
  ASSERT_LT(n, 40);  // a handful
  const TopologyStats stats = engine.retriangulate(true);
  const Snapshot s = read(engine);

  // Kept: the Delaunay triangles whose centroid is inside by more than geps.
  const Triangulation dt = delaunay_triangulate(s.points);
  std::vector<Tri> want;
  int dropped = 0;
  for (const Tri& t : dt.triangles) {
    const Vec2 centroid = (1.0 / 3.0) * (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]);
    if (eval_sdf(c.geometry.view(), centroid) < -c.params.geps * c.h0) {
      want.push_back(t);
    } else {
      ++dropped;
    }
  }
  EXPECT_EQ(canonical(s.triangles), canonical(want));
  EXPECT_EQ(stats.triangles, static_cast<int64_t>(s.triangles.size()));
  // Bars: the unique edges of the kept triangles, nothing else (their count here; their
  // identity through the forces in MovePointsIsDistMeshStepOnTheBarsOfTheKeptTriangles).
  EXPECT_EQ(stats.bars, static_cast<int64_t>(unique_edges(s.triangles).size()));
  if (drops_some) {
    EXPECT_GT(dropped, 0) << "the case should exercise the filter";
  }
}

TEST(CpuEngine, RetriangulateKeepsInsideTrianglesAndTheirUniqueEdges) {
  expect_filtered_delaunay(cluster_problem(), false);
  // G2 at h0 = 0.5: a few points around a hole that Delaunay triangles span (and drop).
  expect_filtered_delaunay(testing::benchmark_problem("G2", 0.5), true);
}

// Repairs (retriangulate(false): Lawson flips from the previous triangulation) must give the
// same kept triangles as a triangulation from scratch of the moved points.
void expect_repairs_match_full_triangulations(const Problem& problem) {
  const CompiledProblem c = compile_problem(problem);
  ThreadPool pool(2);
  CpuEngine engine(pool);
  engine.initialize(c);
  engine.retriangulate(true);
  int repairs = 0;
  int64_t dropped_since_full = 0;
  for (int it = 0; it < 150 && repairs < 6; ++it) {
    const StepResult r = engine.move_points();
    if (!(r.max_drift > c.params.ttol)) continue;
    const TopologyStats stats = engine.retriangulate(false);
    if (stats.full) {  // the repair gave up (an inverted triangle): a rebuild, fine
      dropped_since_full = 0;
      continue;
    }
    ++repairs;
    dropped_since_full += stats.dropped;
    const Snapshot s = read(engine);
    const Triangulation dt = delaunay_triangulate(s.points);
    std::vector<Tri> want;
    for (const Tri& t : dt.triangles) {
      const Vec2 centroid = (1.0 / 3.0) * (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]);
      if (eval_sdf(c.geometry.view(), centroid) < -c.params.geps * c.h0) want.push_back(t);
    }
    const auto got_set = canonical(s.triangles), want_set = canonical(want);
    // A repair may drop turned-over slivers of the boundary layer (lawson_repair.h); until the
    // next rebuild the flips around such a gap may differ from a rebuild there, and only there.
    // Without drops the two must be the same triangles.
    auto in_boundary_layer = [&](const Tri& t) {
      if (dropped_since_full == 0) return false;
      for (int32_t v : t)
        if (eval_sdf(c.geometry.view(), s.points[v]) < -2 * kNearBoundaryRelative * c.h0)
          return false;
      return true;
    };
    size_t missing = 0, extra = 0;
    for (const Tri& t : want_set) missing += got_set.count(t) == 0 && !in_boundary_layer(t);
    for (const Tri& t : got_set) extra += want_set.count(t) == 0 && !in_boundary_layer(t);
    EXPECT_EQ(missing, 0u) << "iteration " << it << ": " << missing << " of " << want_set.size()
                           << " Delaunay triangles missing after " << stats.flips << " flips";
    EXPECT_EQ(extra, 0u) << "iteration " << it;
    EXPECT_EQ(stats.triangles, static_cast<int64_t>(s.triangles.size()));
    EXPECT_EQ(stats.bars, static_cast<int64_t>(unique_edges(s.triangles).size()));
  }
  EXPECT_GT(repairs, 0) << "no repair happened: the test checked nothing";
}

TEST(CpuEngine, RepairedTriangulationEqualsTheFullOne) {
  expect_repairs_match_full_triangulations(testing::benchmark_problem("G5", 0.08));
  expect_repairs_match_full_triangulations(testing::benchmark_problem("G3", 0.06));
  expect_repairs_match_full_triangulations(testing::benchmark_problem("G1", 0.1));
}

// ---- Steps 4-8 ----------------------------------------------------------------------------------

TEST(CpuEngine, MovePointsIsDistMeshStepOnTheBarsOfTheKeptTriangles) {
  for (const Problem& problem : {cluster_problem(), testing::benchmark_problem("G5", 0.25)}) {
    const CompiledProblem c = compile_problem(problem);
    ThreadPool pool(2);
    CpuEngine engine(pool);
    engine.initialize(c);
    engine.retriangulate(true);
    const Snapshot before = read(engine);
    double want_move = 0;
    std::vector<char> projected;
    std::vector<double> unit;
    const std::vector<Vec2> want =
        reference_step(c, before.points, before.triangles, &want_move, &projected, &unit);
    const StepResult r = engine.move_points();
    const Snapshot after = read(engine);
    ASSERT_EQ(after.points.size(), want.size());
    double drift = 0;
    for (size_t i = 0; i < want.size(); ++i) {
      // The projection's finite-difference gradient (step deps = 1.5e-8 h0) turns rounding
      // differences of the force sums (the engine adds them in another order) into ~1e-9 h0.
      const double tol = projected[i] ? 1e-7 * c.h0 : 1e-12;
      EXPECT_NEAR(after.points[i].x, want[i].x, tol) << i;
      EXPECT_NEAR(after.points[i].y, want[i].y, tol) << i;
      drift = std::max(drift, norm(after.points[i] - before.points[i]) / unit[i]);
    }
    EXPECT_NEAR(r.max_move, want_move, 1e-12);
    EXPECT_GT(r.max_move, 0.0);
    // Projected nodes land on the boundary.
    for (size_t i = 0; i < want.size(); ++i) {
      if (projected[i]) {
        EXPECT_LE(std::fabs(eval_sdf(c.geometry.view(), after.points[i])), 1e-6 * c.h0) << i;
      }
    }
    if (!c.size.uniform()) {  // G5: its boundary nodes are pushed out and projected back
      EXPECT_GT(std::count(projected.begin(), projected.end(), 1), 5);
    }
    // The drift is measured from the positions at the last triangulation.
    EXPECT_NEAR(r.max_drift, drift, 1e-12);
  }
}

TEST(CpuEngine, MovePointsPushesACompressedClusterApartAndNeverMovesFixedNodes) {
  const CompiledProblem c = compile_problem(cluster_problem());
  ThreadPool pool(2);
  CpuEngine engine(pool);
  engine.initialize(c);
  engine.retriangulate(true);
  const size_t nfix = c.fixed_points.size();
  auto spread = [&](const std::vector<Vec2>& p) {  // rms distance of the free nodes to their mean
    Vec2 mean{};
    for (size_t i = nfix; i < p.size(); ++i) mean = mean + p[i];
    mean = (1.0 / static_cast<double>(p.size() - nfix)) * mean;
    double s = 0;
    for (size_t i = nfix; i < p.size(); ++i) s += dot(p[i] - mean, p[i] - mean);
    return std::sqrt(s / static_cast<double>(p.size() - nfix));
  };
  auto closest_pair = [&](const std::vector<Vec2>& p) {
    double m = INFINITY;
    for (size_t i = nfix; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j) m = std::min(m, norm(p[i] - p[j]));
    return m;
  };
  std::vector<Vec2> p0;
  engine.read_points(p0);
  ASSERT_EQ(p0.size(), nfix + 9);
  double last_spread = spread(p0), last_closest = closest_pair(p0);
  for (int it = 0; it < 60; ++it) {
    const StepResult r = engine.move_points();
    if (r.max_drift > c.params.ttol) engine.retriangulate(false);
    std::vector<Vec2> p;
    engine.read_points(p);
    for (size_t f = 0; f < nfix; ++f) ASSERT_TRUE(p[f] == c.fixed_points[f]) << "it " << it;
    // Nodes pushed out of the disk are projected back onto it.
    for (size_t i = nfix; i < p.size(); ++i)
      ASSERT_LE(eval_sdf(c.geometry.view(), p[i]), 1e-6 * c.h0) << "it " << it << " node " << i;
    if (it < 2) {
      // While compressed, each step spreads the cluster and separates its closest pair.
      EXPECT_GT(spread(p), last_spread) << "it " << it;
      EXPECT_GT(closest_pair(p), last_closest) << "it " << it;
    }
    last_spread = spread(p);
    last_closest = closest_pair(p);
  }
  // After 60 steps the 9 nodes fill a good part of the disk, not a 0.25-wide patch.
  EXPECT_GT(last_spread, 3 * spread(p0));
}

// ---- Step 6 -------------------------------------------------------------------------------------

TEST(CpuEngine, RemoveCrowdedPointsRemovesEndsOfShortBarsButNeverFixedNodes) {
  const CompiledProblem c = compile_problem(cluster_problem());
  ThreadPool pool(2);
  CpuEngine engine(pool);
  engine.initialize(c);
  engine.retriangulate(true);
  const Snapshot s = read(engine);
  const size_t nfix = c.fixed_points.size();

  // Expected: the free ends of every bar with L0 > 2 L (uniform size: L0 = Fscale * rms(L)).
  const auto bars = unique_edges(s.triangles);
  double sum_l2 = 0;
  for (const Bar& b : bars)
    sum_l2 += dot(s.points[b[0]] - s.points[b[1]], s.points[b[0]] - s.points[b[1]]);
  const double L0 = c.params.fscale * std::sqrt(sum_l2 / static_cast<double>(bars.size()));
  std::vector<char> remove(s.points.size(), 0);
  bool fixed_pair_crowded = false;
  for (const Bar& b : bars) {
    if (!(L0 > 2 * norm(s.points[b[0]] - s.points[b[1]]))) continue;
    if (b[0] < static_cast<int32_t>(nfix) && b[1] < static_cast<int32_t>(nfix))
      fixed_pair_crowded = true;
    for (int32_t e : b)
      if (e >= static_cast<int32_t>(nfix)) remove[e] = 1;
  }
  ASSERT_TRUE(fixed_pair_crowded) << "the 0.001-long bar between two fixed nodes is crowded";
  std::vector<Vec2> want;
  for (size_t i = 0; i < s.points.size(); ++i)
    if (!remove[i]) want.push_back(s.points[i]);
  const int64_t removed = static_cast<int64_t>(s.points.size() - want.size());
  ASSERT_GT(removed, 0);

  EXPECT_EQ(engine.remove_crowded_points(kRemoveAny), removed);
  std::vector<Vec2> got;
  engine.read_points(got);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) EXPECT_TRUE(got[i] == want[i]) << i;
  for (size_t f = 0; f < nfix; ++f) EXPECT_TRUE(got[f] == c.fixed_points[f]);
  EXPECT_EQ(engine.node_count(), static_cast<int64_t>(want.size()));
  // The engine carries on after the full retriangulation the caller must do.
  const TopologyStats t = engine.retriangulate(true);
  EXPECT_GT(t.triangles, 0);
  EXPECT_GE(engine.move_points().max_move, 0.0);
}

TEST(CpuEngine, RemovePointsSkipsFixedAndOutOfRangeIndices) {
  const CompiledProblem c = compile_problem(cluster_problem());
  ThreadPool pool(1);
  CpuEngine engine(pool);
  const int64_t n = engine.initialize(c);
  engine.retriangulate(true);
  std::vector<Vec2> before;
  engine.read_points(before);
  const int32_t nfix = static_cast<int32_t>(c.fixed_points.size());
  engine.remove_points({0, 3, nfix, nfix + 4, static_cast<int32_t>(n), 1000});
  std::vector<Vec2> after;
  engine.read_points(after);
  ASSERT_EQ(static_cast<int64_t>(after.size()), n - 2);
  for (int32_t f = 0; f < nfix; ++f) EXPECT_TRUE(after[f] == before[f]);
  EXPECT_TRUE(after[nfix] == before[nfix + 1]);
  EXPECT_TRUE(after[nfix + 3] == before[nfix + 5]);
}

// ---- Determinism --------------------------------------------------------------------------------

// The engine's points and step results after a few steps of G5 on `pool`: enough bars (~36k)
// for several chunks, so that threads really split the reductions, and a repair or two.
std::pair<std::vector<Vec2>, std::vector<double>> engine_run(const CompiledProblem& c,
                                                             ThreadPool& pool) {
  CpuEngine engine(pool);
  engine.initialize(c);
  engine.retriangulate(true);
  std::vector<double> moves;
  for (int it = 0; it < 8; ++it) {
    const StepResult r = engine.move_points();
    moves.insert(moves.end(), {r.max_move, r.max_drift, r.rms_move});
    if (r.max_drift > c.params.ttol)
      moves.push_back(static_cast<double>(engine.retriangulate(false).flips));
  }
  moves.push_back(static_cast<double>(engine.remove_crowded_points(kRemoveAny)));
  std::vector<Vec2> p;
  engine.read_points(p);
  return {p, moves};
}

bool same_points(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](Vec2 p, Vec2 q) { return p == q; });
}

TEST(CpuEngine, SameBitsForAnyNumberOfThreadsAndRepeatedRuns) {
  const CompiledProblem c = compile_problem(testing::benchmark_problem("G5", 0.01));
  ThreadPool one(1), two(2), four(4);
  const auto first = engine_run(c, one);
  EXPECT_GT(first.first.size(), 10000u);
  // Other allocations in between, as in a service between two jobs: the engine's results must
  // not depend on the heap's state (the bar order once followed CGAL's face addresses).
  std::vector<std::vector<char>> heap_noise;
  for (int i = 0; i < 5000; ++i) heap_noise.emplace_back(1000 + 37 * i);
  for (ThreadPool* pool : {&two, &four, &one}) {
    const auto again = engine_run(c, *pool);
    EXPECT_TRUE(same_points(again.first, first.first)) << pool->size() << " threads";
    EXPECT_EQ(again.second, first.second) << pool->size() << " threads";
  }
}

}  // namespace
}  // namespace meshd
