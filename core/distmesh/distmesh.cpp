#include "core/distmesh/distmesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh/assemble_mesh.h"
#include "core/distmesh/gap_points.h"
#include "core/distmesh/node_estimate.h"
#include "core/distmesh/optimize_worst.h"
#include "core/distmesh/removal_limit.h"
#include "core/distmesh/smooth_mean_quality.h"
#include "core/distmesh/trapped_nodes.h"

namespace meshd {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The coarsest level aims at [kCoarsestNodes, 4 kCoarsestNodes) nodes: large enough that its
// mesh resolves the geometry, small enough that its slow global relaxation is cheap.
constexpr double kCoarsestNodes = 2000.0;
// ... and at least this many nodes per fixed node. Every level keeps all the fixed nodes, so a
// level with fewer nodes than that is mostly fixed nodes, too dense for its size field; its
// L0 scale follows its own density, and each refinement passes the excess on four times over. A
// coastline with 21k fixed shoreline vertices, meshed in five levels (the coarsest asked for 2.6k
// nodes and had 21.5k), came out with 2.8M nodes against an estimate of 0.67M. At 4 per fixed
// node the coastline's 1M nodes still took two levels, and its mesh was worse than one level's
// in about the same time (q_mean 0.9838 against 0.9857, 24 triangles under q 0.6 against 9).
constexpr double kNodesPerFixedNode = 16.0;

std::vector<CompiledProblem> multilevel_problems(const CompiledProblem& problem, ThreadPool* pool) {
  int coarsenings = 0;
  const Params::Multilevel mode = problem.params.multilevel;
  const bool on = mode == Params::Multilevel::kOn ||
                  (mode == Params::Multilevel::kAuto && !problem.size.uniform());
  const double nodes = on ? estimate_node_count(problem, pool) : 0.0;
  const auto fixed = static_cast<double>(problem.fixed_points.size());
  const double fewest = std::max(kCoarsestNodes, kNodesPerFixedNode * fixed);
  for (double n = nodes; n >= 4.0 * fewest; n /= 4.0) ++coarsenings;
  std::vector<CompiledProblem> levels;
  for (int k = coarsenings; k >= 0; --k) {
    levels.push_back(problem);
    levels.back().h0 = std::ldexp(problem.h0, k);
  }
  return levels;
}

// One run of the loop: the counters, the timers and the observer calls in one place.
class Loop {
 public:
  Loop(const CompiledProblem& problem, Engine& engine, Observer* observer,
       const std::atomic<bool>* cancel)
      : problem_(problem), engine_(engine), observer_(observer), cancel_(cancel) {}

  MeshResult run() {
    const auto t0 = Clock::now();
    MeshResult result;
    RunStats& s = stats_;

    // Multilevel: levels[0] is the coarsest (h0 * 2^L), levels[L] the problem itself.
    const std::vector<CompiledProblem> levels = multilevel_problems(problem_, engine_.host_pool());
    for (size_t level = 0; level < levels.size(); ++level) {
      current_ = &levels[level];
      auto t = Clock::now();
      if (level == 0) {
        // 1-2. Initial points.
        engine_.initialize(*current_);
      } else {
        refine_and_fill_gaps();
      }
      s.t_initial += seconds_since(t);
      triangulate(true);
      // 3-8. Relax until the interior has settled (the termination test of params.h). A coarser
      // level only prepares the next one's start: the coarser levels share at most half of
      // max_iterations, so that one that never settles (features below its resolution) cannot
      // leave the problem itself unrelaxed, and each ends once its rms move stops falling fast.
      const int before = s.iterations;
      const int left = current_->params.max_iterations - s.iterations;
      const int coarser_levels = static_cast<int>(levels.size()) - 1;
      const bool coarser = static_cast<int>(level) < coarser_levels;
      const int budget = std::max(
          1,
          coarser ? std::min(left, current_->params.max_iterations / (2 * coarser_levels)) : left);
      s.converged = relax(budget, true, s.iterations, coarser);
      s.equivalent_iterations +=
          (s.iterations - before) * static_cast<double>(engine_.node_count());
    }
    s.levels = static_cast<int>(levels.size());
    s.equivalent_iterations /= static_cast<double>(engine_.node_count());
    current_ = &problem_;

    // Boundary clean-up: remove the middle node of boundary slivers, then relax again.
    if (problem_.params.cleanup) {
      const auto t = Clock::now();
      for (int round = 0; round < kCleanupRounds; ++round) {
        // The clean-up's relaxation counts against max_iterations too.
        const int budget = std::min(kCleanupIterations, problem_.params.max_iterations -
                                                            s.iterations - s.cleanup_iterations);
        if (budget <= 0) break;
        const int64_t removed = engine_.remove_boundary_slivers(problem_, max_removed());
        if (removed == 0) break;
        s.cleanup_removed += removed;
        triangulate(true);
        relax(budget, false, s.cleanup_iterations);
      }
      s.t_cleanup += seconds_since(t);
    }

    // The points moved a little since the last triangulation: triangulate once more so that the
    // result is the Delaunay mesh of its own nodes; from scratch when a repair dropped collapsed
    // boundary slivers since the last full triangulation, which may have left a gap.
    const auto t_finish = Clock::now();
    triangulate(false);
    if (dropped_since_full_ > 0) triangulate(true);
    // The boundary depends on the triangles alone, which the optimisation keeps: found once (the
    // trapped nodes' removal carries it over to the triangles it leaves).
    MeshCopy copy;
    engine_.read_mesh(copy);
    if (problem_.params.cleanup) {
      const auto t = Clock::now();
      s.trapped_removed =
          remove_trapped_nodes(copy, static_cast<int32_t>(problem_.fixed_points.size()));
      s.smoothed_moves = smooth_mean_quality(problem_, copy.points, copy.triangles, copy.boundary,
                                             engine_.host_pool());
      s.optimized_moves =
          optimize_worst_elements(problem_, copy.points, copy.triangles, copy.boundary,
                                  copy.below ? &*copy.below : nullptr, engine_.host_pool());
      s.t_cleanup += seconds_since(t);
    }
    result.mesh = assemble_mesh(problem_, std::move(copy.points), std::move(copy.triangles),
                                copy.boundary, copy.tidy);
    result.quality = engine_.measure_quality(
        result.mesh, s.smoothed_moves > 0 || s.optimized_moves > 0 || s.trapped_removed > 0);
    s.t_finish = seconds_since(t_finish);
    s.t_total = seconds_since(t0);
    result.stats = s;
    return result;
  }

 private:
  static constexpr int kCleanupRounds = 3;
  static constexpr int kCleanupIterations = 200;
  // The termination test's constants (step_rule.cuh).
  static constexpr double kMaxMoveFactor = 10.0;
  static constexpr int kMinIterations = 10;
  static constexpr int kPatience = 100;
  static constexpr int kCoarserLevelRmsPatience = 100;
  static constexpr double kCoarserLevelRmsProgress = 0.75;

  int64_t max_removed() const {
    const auto free_nodes =
        engine_.node_count() - static_cast<int64_t>(current_->fixed_points.size());
    return most_removed_at_once(free_nodes);
  }

  // The next level: the engine's refinement, then nodes where the coarser mesh left part of the
  // domain without triangles (gap_points.h), appended, so that the engine's refined nodes keep
  // their numbers. Every refinement reads the coarse mesh to the host; the grid is searched while
  // an engine that refines on a device may still be at it, and only where the search finds
  // uncovered points are the refined nodes read and, where some are needed, loaded again.
  void refine_and_fill_gaps() {
    std::vector<Vec2> coarse_points;
    std::vector<std::array<int32_t, 3>> coarse_triangles;
    engine_.read_points(coarse_points);
    engine_.read_triangles(coarse_triangles);
    engine_.refine(*current_);
    const std::vector<Vec2> uncovered =
        uncovered_grid_points(*current_, coarse_points, coarse_triangles, engine_.host_pool());
    if (uncovered.empty()) return;
    std::vector<Vec2> nodes;
    engine_.read_points(nodes);
    const std::vector<Vec2> gaps = away_from_nodes(*current_, uncovered, nodes);
    if (gaps.empty()) return;
    stats_.gap_nodes += static_cast<int64_t>(gaps.size());
    nodes.insert(nodes.end(), gaps.begin(), gaps.end());
    engine_.load_points(*current_, nodes);
  }

  void triangulate(bool full) {
    const auto t = Clock::now();
    const TopologyStats topo = engine_.retriangulate(full);
    count_triangulation(topo, seconds_since(t));
  }
  // Step 3 and the steps after it, where the engine starts the steps behind the repair (one wait
  // for both; their time counts as the triangulation's). Returns whether it did.
  bool triangulate_and_move(const StepRule& rule, int it, int limit) {
    const auto t = Clock::now();
    const std::optional<TopologyStats> topo =
        engine_.retriangulate_and_move(rule, it, limit, steps_);
    if (topo) count_triangulation(*topo, seconds_since(t));
    return topo.has_value();
  }
  void count_triangulation(const TopologyStats& topo, double seconds) {
    stats_.t_triangulation += seconds;
    ++stats_.retriangulations;
    if (topo.full) {
      stats_.t_full_triangulation += seconds;
      ++stats_.full_triangulations;
      dropped_since_full_ = 0;
    }
    dropped_since_full_ += topo.dropped;
    if (topo.repair_failed) ++stats_.repair_fallbacks;
    if (topo.folds_refilled) ++stats_.fold_refills;
    stats_.flips += topo.flips;
    drift_ = 0.0;
    ++topology_version_;
  }

  // Steps 3-8 for at most `max_iterations`; adds the iterations run to `iterations`. Returns
  // whether the termination test passed. A coarser level (`prepares_next_level`) also ends once
  // its rms move stops falling fast (StepRule::rms_patience).
  bool relax(int max_iterations, bool density_control, int& iterations,
             bool prepares_next_level = false) {
    const Params& prm = current_->params;
    const int interval = density_control ? prm.density_control_interval : 0;
    StepRule rule;
    rule.ttol = prm.ttol;
    rule.dptol = prm.dptol;
    rule.max_move_factor = kMaxMoveFactor;
    rule.min_iterations = kMinIterations;
    rule.patience = kPatience;
    if (prepares_next_level) {
      rule.rms_patience = kCoarserLevelRmsPatience;
      rule.rms_progress = kCoarserLevelRmsProgress;
    }
    int it = 1;
    while (it <= max_iterations) {
      check_cancel();
      ++iterations;
      // 3. Retriangulate once some node drifted ttol * h0 from where it was triangulated: here
      // before density control, otherwise with the steps below.
      const bool density_now = interval > 0 && it % interval == 0;
      const bool retriangulate_now = rule.needs_triangulation(drift_);
      if (retriangulate_now && density_now) triangulate(false);
      // 6. Density control.
      if (density_now) {
        const auto t = Clock::now();
        const int64_t removed = engine_.remove_crowded_points(max_removed());
        stats_.t_density += seconds_since(t);
        if (removed > 0) {
          stats_.density_removed += removed;
          triangulate(true);
          ++it;
          continue;
        }
      }
      // 4-5, 7-8. Forces, Euler step, projection: as many steps at once as the engine likes, up
      // to the next density control or snapshot; the engine stops after a step that calls for
      // step 3 or passes step 8, so each iteration of the batch is one that this loop would run.
      int limit = std::min(engine_.preferred_batch(), max_iterations - it + 1);
      if (interval > 0) limit = std::min(limit, interval - it % interval);
      limit = up_to_snapshot(limit);
      steps_.clear();
      const bool with_steps = retriangulate_now && !density_now;
      if (!with_steps || !triangulate_and_move(rule, it, limit)) {
        if (with_steps) triangulate(false);
        const auto t = Clock::now();
        engine_.move_points_until(rule, it, limit, steps_);
        stats_.t_forces += seconds_since(t);
      }
      for (size_t k = 0; k < steps_.size(); ++k, ++it) {
        if (k > 0) {
          check_cancel();
          ++iterations;
        }
        drift_ = steps_[k].max_drift;
        rule.settling = rule.settle(rule.settling, steps_[k]);
        report(stats_.iterations + stats_.cleanup_iterations, steps_[k].max_move);
        // 8. Termination (step_rule.cuh).
        if (rule.converged(steps_[k], it, rule.settling)) return true;
      }
    }
    return false;
  }

  void check_cancel() const {
    if (cancel_ != nullptr && cancel_->load(std::memory_order_relaxed))
      throw Error(ErrorCode::kCancelled, "", "the job was cancelled");
  }

  // Shortens a batch of `limit` steps so that it ends at the first of its iterations that the
  // observer wants a snapshot of. Each iteration number is asked about once, in order.
  int up_to_snapshot(int limit) {
    if (observer_ == nullptr) return limit;
    const int first = stats_.iterations + stats_.cleanup_iterations;  // the batch's first step
    for (int k = 0; k < limit; ++k) {
      const int number = first + k;
      if (number > asked_through_) {
        asked_through_ = number;
        if (observer_->wants_snapshot(number)) snapshot_at_ = number;
      }
      if (number == snapshot_at_) return k + 1;
    }
    return limit;
  }

  void report(int iteration, double max_move) {
    if (observer_ == nullptr) return;
    Progress p;
    p.iteration = iteration;
    p.max_move = max_move;
    p.retriangulations = stats_.retriangulations;
    p.flips = stats_.flips;
    p.nodes = engine_.node_count();
    p.elapsed_s = seconds_since(start_);
    observer_->on_progress(p);
    if (iteration != snapshot_at_) return;
    engine_.read_points(points_);
    const bool changed = topology_version_ != snapshot_version_;
    if (changed) engine_.read_triangles(triangles_);
    snapshot_version_ = topology_version_;
    observer_->on_snapshot(iteration, points_, changed ? &triangles_ : nullptr);
  }

  const CompiledProblem& problem_;
  const CompiledProblem* current_ = &problem_;  // the level being relaxed
  Engine& engine_;
  Observer* observer_;
  const std::atomic<bool>* cancel_;
  const Clock::time_point start_ = Clock::now();
  RunStats stats_;
  double drift_ = 0.0;
  int64_t dropped_since_full_ = 0;
  int64_t topology_version_ = 0;
  int64_t snapshot_version_ = -1;
  int asked_through_ = 0;  // the last iteration number the observer was asked about
  int snapshot_at_ = 0;    // the iteration it wants a snapshot of next
  std::vector<StepResult> steps_;
  std::vector<Vec2> points_;
  std::vector<std::array<int32_t, 3>> triangles_;
};

}  // namespace

MeshResult generate_mesh(const CompiledProblem& problem, Engine& engine, Observer* observer,
                         const std::atomic<bool>* cancel) {
  return Loop(problem, engine, observer, cancel).run();
}

}  // namespace meshd
