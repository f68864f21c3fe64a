#include "core/distmesh3d/distmesh3d.h"

#include <chrono>

#include "core/common/error.h"
#include "core/distmesh3d/initial_points3d.h"
#include "core/distmesh3d/optimize_slivers3d.h"
#include "core/distmesh3d/settle_surface3d.h"
#include "core/distmesh3d/step3d.h"
#include "core/distmesh3d/topology3d.h"

namespace meshd {
namespace {

// Nodes closer than this (times h0) are one node (Topology3::coincident).
constexpr double kCoincidentRelative = 0.01;

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
                    Observer* observer, const std::atomic<bool>* cancel) {
  const auto check_cancel = [cancel] {
    if (cancel != nullptr && cancel->load(std::memory_order_relaxed))
      throw Error(ErrorCode::kCancelled, "", "the job was cancelled");
  };
  if (!(h0 > 0.0)) throw Error(ErrorCode::kInvalidArgument, "h0", "must be > 0");
  const double geps = params.geps * h0;

  const auto start = std::chrono::steady_clock::now();
  // 1-2. Initial nodes, fixed first.
  Nodes3 nodes;
  nodes.points = initial_points3d(domain, h0, params.geps, params.seed);
  nodes.fixed = static_cast<int64_t>(domain.fixed.size());
  nodes.momentum.assign(nodes.points.size(), Vec3{});
  nodes.at_triangulation = nodes.points;

  StepRule rule;
  rule.ttol = params.ttol;
  rule.dptol = params.dptol;
  rule.max_move_factor = params.max_move_factor;
  rule.patience = params.patience;

  Relaxed3 stats;
  // Step 3, after taking out the free nodes that coincide with another (Topology3::coincident).
  const auto triangulate = [&](Nodes3& n, Relaxed3& counts) {
    for (;;) {
      Topology3 t = triangulate3d(domain, n.points, n.fixed, geps, kCoincidentRelative * h0, pool);
      n.at_triangulation = n.points;
      if (t.coincident.empty()) return t;
      remove_nodes3d(n, t.coincident);
      counts.removed += static_cast<int64_t>(t.coincident.size());
    }
  };
  Topology3 topology;
  BarLengths bars;
  bool retriangulate = true;
  for (int iteration = 1; iteration <= params.max_iterations; ++iteration) {
    check_cancel();
    // 3. Retriangulate once a node drifted ttol of its length.
    if (retriangulate) {
      topology = triangulate(nodes, stats);
      ++stats.retriangulations;
    }
    // 4, 5, 7, 8. Forces, move, projection.
    const StepResult step = step3d(domain, params, h0, topology, nodes, bars, pool);
    stats.iterations = iteration;
    if (observer != nullptr) {
      Progress progress;
      progress.iteration = iteration;
      progress.max_move = step.max_move;
      progress.retriangulations = stats.retriangulations;
      progress.nodes = static_cast<int64_t>(nodes.points.size());
      progress.elapsed_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      observer->on_progress(progress);
    }
    rule.settling = rule.settle(rule.settling, step);
    if (rule.converged(step, iteration, rule.settling)) {
      stats.converged = true;
      break;
    }
    retriangulate = rule.needs_triangulation(step.max_drift);
    // 6. Density control on this step's bars: both ends of a bar far shorter than it should be.
    if (params.density_control_interval > 0 && iteration % params.density_control_interval == 0) {
      const std::vector<int32_t> crowded = crowded_nodes3d(topology, bars, nodes.fixed);
      if (!crowded.empty()) {
        remove_nodes3d(nodes, crowded);
        stats.removed += static_cast<int64_t>(crowded.size());
        retriangulate = true;
      }
    }
  }

  // The final nodes' own tetrahedra: the last steps moved them since the last triangulation.
  topology = triangulate(nodes, stats);
  const auto relaxed = std::chrono::steady_clock::now();
  // The finish: the surface onto the boundary, then the slivers the forces leave.
  check_cancel();
  const SurfaceSettling surface =
      settle_surface3d(domain, params.deps * h0, nodes.points, topology.tets, nodes.fixed, pool);
  Relaxed3 out = compact(std::move(nodes.points), std::move(topology.tets), nodes.fixed);
  out.surface = surface;
  out.iterations = stats.iterations;
  out.retriangulations = stats.retriangulations + 1;
  out.removed = stats.removed;
  out.converged = stats.converged;
  out.t_relax = std::chrono::duration<double>(relaxed - start).count();
  if (params.optimize_slivers) {
    check_cancel();
    out.optimizer_moves =
        optimize_slivers3d(domain, params.deps * h0, out.points, out.tets, out.fixed, pool);
  }
  out.t_slivers = std::chrono::duration<double>(std::chrono::steady_clock::now() - relaxed).count();
  return out;
}

}  // namespace meshd
