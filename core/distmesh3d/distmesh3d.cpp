#include "core/distmesh3d/distmesh3d.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "core/common/error.h"
#include "core/delaunay/delaunay3d.h"
#include "core/delaunay/flip_repair3.h"
#include "core/distmesh/removal_limit.h"
#include "core/distmesh3d/cpu_engine3.h"
#include "core/distmesh3d/initial_points3d.h"
#include "core/distmesh3d/optimize_slivers3d.h"
#include "core/distmesh3d/settle_surface3d.h"
#include "core/distmesh3d/step3d.h"
#include "core/distmesh3d/topology3d.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// Nodes closer than this (times h0) are one node (Topology3::coincident).
constexpr double kCoincidentRelative = 0.01;
// A retriangulation moves only the nodes that drifted half of ttol of their bars' length, when
// they are at most this share of all and this many: most of a run's retriangulations are called
// for by a handful of nodes (a node beside a fixed one, or one the projection moves along a
// crease), and moving those few in the kept triangulation costs a fraction of building it anew.
// Each move (a removal and an insertion) runs on one thread, hence the count's cap.
constexpr double kPartialShare = 0.02;
constexpr size_t kPartialMost = 1000;
// The share of a repair's tetrahedra that may lie inside turned over (and go, see `serves`): the
// repairs of a 1,800-node ball (9k tetrahedra) left 0 or 6 such, or 66 to 377 where boundary
// nodes had slid far, which this refuses.
constexpr double kTurnedInsideShare = 1e-3;

// The tetrahedra's points, the used fixed ones first, the others in first use order,
// renumbered; points no kept tetrahedron uses go: free ones outside or cut off by the centroid
// filter, and fixed ones whose every tetrahedron was flat (a sample along a straight edge
// between two neighbours on it, which the mesh's edge then follows all the same).
Relaxed3 compact(std::vector<Vec3> points, std::vector<std::array<int32_t, 4>> tets,
                 int64_t fixed) {
  std::vector<int32_t> index(points.size(), -1);
  std::vector<char> used(points.size(), 0);
  for (const auto& t : tets)
    for (int32_t v : t) used[v] = 1;
  Relaxed3 out;
  for (int64_t i = 0; i < fixed; ++i) {
    if (!used[i]) {
      ++out.unused_fixed;
      continue;
    }
    index[i] = static_cast<int32_t>(out.points.size());
    out.points.push_back(points[i]);
  }
  out.fixed = fixed - out.unused_fixed;
  for (auto& t : tets)
    for (int32_t& v : t) {
      if (index[v] < 0) {
        index[v] = static_cast<int32_t>(out.points.size());
        out.points.push_back(points[v]);
      }
      v = index[v];
    }
  out.tets = std::move(tets);
  return out;
}

}  // namespace

Relaxed3 distmesh3d(const Domain3& domain, double h0, const Params3& params, ThreadPool* pool,
                    Observer* observer, const std::atomic<bool>* cancel, Engine3* engine) {
  CpuEngine3 cpu(pool);
  if (engine == nullptr) engine = &cpu;
  const auto check_cancel = [cancel] {
    if (cancel != nullptr && cancel->load(std::memory_order_relaxed))
      throw Error(ErrorCode::kCancelled, "", "the job was cancelled");
  };
  if (!(h0 > 0.0)) throw Error(ErrorCode::kInvalidArgument, "h0", "must be > 0");
  engine->begin(domain, h0, params);
  const double geps = params.geps * h0;

  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  const auto start = Clock::now();
  // 1-2. Initial nodes, fixed first.
  Nodes3 nodes;
  nodes.points = initial_points3d(domain, h0, params.geps, params.seed);
  nodes.fixed = static_cast<int64_t>(domain.fixed.size());
  nodes.momentum.assign(nodes.points.size(), Vec3{});
  nodes.at_triangulation = nodes.points;
  Relaxed3 stats;
  stats.t_initial = seconds_since(start);

  StepRule rule;
  rule.ttol = params.ttol;
  rule.dptol = params.dptol;
  rule.max_move_factor = params.max_move_factor;
  rule.patience = params.patience;

  // Step 3, after taking out the free nodes that coincide with another (Topology3::coincident):
  // the engine's kept triangulation repaired for the moved nodes (`repair`), or the nodes
  // `moved` moved in the host's kept triangulation (which lost the nodes removed since), or (none
  // given, or a repair or move that failed) all of them triangulated anew. Tells whether it was
  // repaired on the engine, moved on the host, or built.
  Tetrahedralization3 delaunay;
  enum class Made { kRepaired, kMoved, kBuilt };
  // A repair leaves turned over the tetrahedra its flips could not mend: mostly flat ones of
  // four boundary nodes, outside, which the hull's fixed faces hold (flip_repair3.h). They go;
  // the repair serves unless more than a few of them lay inside, where the tetrahedra around
  // them overlap. The engine keeps them, and a later repair that they make fail builds anew.
  const auto serves = [&](const std::vector<Vec3>& points,
                          std::vector<std::array<int32_t, 4>>& all) {
    const std::vector<std::array<int32_t, 4>> turned = take_turned3(points, all);
    const auto inside = std::count_if(turned.begin(), turned.end(), [&](const auto& t) {
      const Vec3 c = 0.25 * (points[t[0]] + points[t[1]] + points[t[2]] + points[t[3]]);
      return domain.distance(c) < -geps;
    });
    return static_cast<double>(inside) <= kTurnedInsideShare * static_cast<double>(all.size());
  };
  const auto triangulate = [&](Nodes3& n, Relaxed3& counts, bool repair,
                               const std::optional<std::vector<int32_t>>& moved, Topology3& t) {
    const auto begin = Clock::now();
    std::optional<std::vector<std::array<int32_t, 4>>> all;
    const auto tetrahedralize = [&](auto&& make) {
      const auto t0 = Clock::now();
      all = make();
      counts.t_delaunay += seconds_since(t0);
    };
    Made made = Made::kBuilt;
    if (repair) tetrahedralize([&] { return engine->repair_triangulation(); });
    if (all) {
      delaunay.forget();  // its points are where the last build or move left them
      n.at_triangulation = n.points;
      if (serves(n.points, *all)) {
        made = Made::kRepaired;
      } else {
        all.reset();
        ++counts.repairs_refused;
      }
    } else if (moved) {
      tetrahedralize([&] { return delaunay.move(n.points, *moved); });
      if (all) {
        made = Made::kMoved;
        for (int32_t i : *moved) n.at_triangulation[i] = n.points[i];
      }
    }
    bool renumbered = false;  // the engine's repaired triangulation is no longer the nodes'
    for (;;) {
      if (!all) {
        tetrahedralize([&] { return delaunay.build(n.points, pool_threads(pool)); });
        n.at_triangulation = n.points;
      }
      t = topology_of3d(domain, n.points, *all, n.fixed, geps, kCoincidentRelative * h0, pool);
      if (t.coincident.empty()) break;
      remove_nodes3d(n, t.coincident);
      renumbered = true;
      counts.removed += static_cast<int64_t>(t.coincident.size());
      all.reset();
      if (delaunay.remove(t.coincident))
        tetrahedralize([&] { return delaunay.move(n.points, {}); });
    }
    if (repair && (made != Made::kRepaired || renumbered))
      engine->keep_triangulation(*all, static_cast<int64_t>(n.points.size()));
    counts.t_triangulate += seconds_since(begin);
    return made;
  };
  Topology3 topology;
  bool retriangulate = true;
  bool topology_streamed = false;  // the last snapshot carried the current tetrahedra
  int last_partial = -1;           // the iteration of the last partial retriangulation
  for (int iteration = 1; iteration <= params.max_iterations; ++iteration) {
    check_cancel();
    // 3. Retriangulate once a node drifted ttol of its length.
    if (retriangulate) {
      engine->sync();
      std::optional<std::vector<int32_t>> moved;
      // Not before the first triangulation (which measures the nodes' spacing); two partial ones
      // in a row would mean the drifting node was not among those moved.
      if (!nodes.spacing.empty() && last_partial != iteration - 1) {
        moved = drifted_nodes3d(nodes, 0.5 * params.ttol);
        if (moved->size() > kPartialMost ||
            static_cast<double>(moved->size()) > kPartialShare * nodes.points.size())
          moved.reset();
      }
      switch (triangulate(nodes, stats, true, moved, topology)) {
        case Made::kRepaired:
          ++stats.repaired_retriangulations;
          break;
        case Made::kMoved:
          last_partial = iteration;
          ++stats.partial_retriangulations;
          break;
        case Made::kBuilt:
          break;
      }
      measure_spacing3d(topology, nodes);
      engine->start(nodes, topology);
      ++stats.retriangulations;
      topology_streamed = false;
    }
    // 4, 5, 7, 8. Forces, move, projection.
    const StepResult step = engine->step();
    stats.iterations = iteration;
    if (observer != nullptr) {
      Progress progress;
      progress.iteration = iteration;
      progress.max_move = step.max_move;
      progress.retriangulations = stats.retriangulations;
      progress.nodes = static_cast<int64_t>(nodes.points.size());
      progress.elapsed_s = seconds_since(start);
      observer->on_progress(progress);
      if (observer->wants_snapshot(iteration)) {
        engine->sync();
        observer->on_volume_snapshot(iteration, nodes.points,
                                     topology_streamed ? nullptr : &topology.tets);
        topology_streamed = true;
      }
    }
    rule.settling = rule.settle(rule.settling, step);
    if (rule.converged(step, iteration, rule.settling)) {
      stats.converged = true;
      break;
    }
    retriangulate = rule.needs_triangulation(step.max_drift);
    // 6. Density control on this step's bars: both ends of a bar far shorter than it should be,
    // unless that is too many at once (removal_limit.h).
    if (params.density_control_interval > 0 && iteration % params.density_control_interval == 0) {
      const std::vector<int32_t> crowded = engine->crowded_nodes();
      const auto free_nodes = static_cast<int64_t>(nodes.points.size()) - nodes.fixed;
      if (!crowded.empty() &&
          static_cast<int64_t>(crowded.size()) <= most_removed_at_once(free_nodes)) {
        engine->sync();
        remove_nodes3d(nodes, crowded);
        engine->forget_triangulation();
        delaunay.remove(crowded);  // a triangulation lost here is built anew at step 3
        stats.removed += static_cast<int64_t>(crowded.size());
        retriangulate = true;
      }
    }
  }

  // The final nodes' own tetrahedra: the last steps moved them since the last triangulation.
  engine->sync();
  triangulate(nodes, stats, false, std::nullopt, topology);
  // A tetrahedron of four coplanar or collinear nodes that the centroid filter kept has no
  // volume and, when its nodes are fixed (samples on a plane through the interior, as a
  // polyhedron whose surface crosses itself makes, or along a straight edge), nothing can mend
  // it: what the validity check would refuse goes.
  std::erase_if(topology.tets, [&](const std::array<int32_t, 4>& t) {
    const auto& p = nodes.points;
    return degenerate_tet(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  });
  const auto relaxed = Clock::now();
  // The finish: the surface onto the boundary, then the slivers the forces leave.
  check_cancel();
  const SurfaceSettling surface =
      settle_surface3d(domain, params.deps * h0, nodes.points, topology.tets, nodes.fixed, pool);
  Relaxed3 out = compact(std::move(nodes.points), std::move(topology.tets), nodes.fixed);
  out.surface = surface;
  out.iterations = stats.iterations;
  out.retriangulations = stats.retriangulations + 1;
  out.partial_retriangulations = stats.partial_retriangulations;
  out.repaired_retriangulations = stats.repaired_retriangulations;
  out.repairs_refused = stats.repairs_refused;
  out.removed = stats.removed;
  out.converged = stats.converged;
  out.t_relax = std::chrono::duration<double>(relaxed - start).count();
  out.t_initial = stats.t_initial;
  out.t_triangulate = stats.t_triangulate;
  out.t_delaunay = stats.t_delaunay;
  out.t_steps = out.t_relax - out.t_initial - out.t_triangulate;
  if (params.optimize_slivers) {
    check_cancel();
    out.optimizer_moves =
        optimize_slivers3d(domain, params.deps * h0, out.points, out.tets, out.fixed, pool);
  }
  out.t_slivers = seconds_since(relaxed);
  return out;
}

}  // namespace meshd
