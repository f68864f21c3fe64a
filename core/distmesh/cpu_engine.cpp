#include "core/distmesh/cpu_engine.h"

#include <algorithm>
#include <cmath>

#include "core/delaunay/delaunay.h"
#include "core/delaunay/lawson_repair.h"
#include "core/delaunay/refill_folds.h"
#include "core/distmesh/initial_points.cuh"
#include "core/geometry/projection.cuh"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// Fixed chunk sizes keep reductions independent of the thread count (thread_pool.h).
constexpr size_t kChunk = 8192;

}  // namespace

// ---- Steps 1-2: initial points --------------------------------------------------------------

int64_t CpuEngine::initialize(const CompiledProblem& problem) {
  problem_ = &problem;
  const double h0 = problem.h0, geps = problem.params.geps * h0;
  const InitialGrid grid = make_initial_grid(problem.bbox, h0);
  const ProgramView fd = problem.geometry.view();
  const SizeView fh = problem.size.view();

  // Inside points and their sizes.
  const int64_t total = grid.nx * grid.ny;
  std::vector<double> size(static_cast<size_t>(total), 0.0);
  std::vector<double> chunk_min(ThreadPool::chunk_count(total, kChunk), INFINITY);
  pool_.for_chunks(total, kChunk, [&](size_t c, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const Vec2 q = initial_grid_point(grid, static_cast<int64_t>(k));
      if (eval_sdf(fd, q) >= geps) continue;
      size[k] = eval_size(fh, q);
      chunk_min[c] = std::min(chunk_min[c], size[k]);
    }
  });
  const double h_min = *std::min_element(chunk_min.begin(), chunk_min.end());

  p_.assign(problem.fixed_points.begin(), problem.fixed_points.end());
  nfix_ = static_cast<int64_t>(p_.size());
  for (int64_t k = 0; k < total; ++k) {
    if (size[k] <= 0.0 || !keep_by_size(problem.seed, grid, k, size[k], h_min)) continue;
    const Vec2 q = initial_grid_point(grid, k);
    // A grid point on top of a fixed node would only be pushed away again.
    bool near_fixed = false;
    for (int64_t f = 0; f < nfix_ && !near_fixed; ++f)
      near_fixed = norm(q - p_[f]) < 0.5 * h0 * size[k];
    if (!near_fixed) p_.push_back(q);
  }
  reset_node_state();
  return node_count();
}

int64_t CpuEngine::load_points(const CompiledProblem& problem, const std::vector<Vec2>& points) {
  problem_ = &problem;
  p_ = points;
  nfix_ = static_cast<int64_t>(problem.fixed_points.size());
  reset_node_state();
  return node_count();
}

// ---- Step 3: triangulation -------------------------------------------------------------------

TopologyStats CpuEngine::retriangulate(bool full) {
  TopologyStats stats;
  stats.full = full || dt_.triangles.empty();
  if (!stats.full) {
    const RepairResult repair = lawson_repair(p_, dt_keep_, on_boundary_, dt_);
    stats.flips = repair.flips;
    stats.dropped = repair.dropped;
    if (!repair.ok) {
      // A triangle turned over since the last triangulation: flips cannot repair that, but
      // the fold is local (refill_folds.h).
      Triangulation refilled = refill_folds(p_, dt_, static_cast<int32_t>(nfix_));
      if (!refilled.triangles.empty()) {
        const std::vector<char> every(refilled.triangles.size(), 1);
        const RepairResult again = lawson_repair(p_, every, on_boundary_, refilled);
        stats.folds_refilled = again.ok;
        if (again.ok) {
          dt_ = std::move(refilled);
          stats.flips = again.flips;
        }
      }
      stats.full = stats.repair_failed = !stats.folds_refilled;
    }
  }
  if (stats.full) dt_ = delaunay_triangulate(p_);

  const ProgramView fd = problem_->geometry.view();
  const double geps = problem_->params.geps * problem_->h0;
  std::vector<char>& keep = dt_keep_;
  keep.assign(dt_.triangles.size(), 0);
  pool_.for_chunks(dt_.triangles.size(), kChunk, [&](size_t, size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const auto& tri = dt_.triangles[t];
      const Vec2 v[3] = {p_[tri[0]], p_[tri[1]], p_[tri[2]]};
      const float c[3] = {clearance_[tri[0]], clearance_[tri[1]], clearance_[tri[2]]};
      const Vec2 centroid = (1.0 / 3.0) * (v[0] + v[1] + v[2]);
      keep[t] = clearance_rule_.centroid_inside(c, v, centroid) || eval_sdf(fd, centroid) < -geps;
    }
  });
  triangles_.clear();
  for (size_t t = 0; t < dt_.triangles.size(); ++t)
    if (keep[t]) triangles_.push_back(dt_.triangles[t]);
  bars_ = edges_of_kept(dt_, keep);
  bar_size_.clear();  // measured again at the new bars' midpoints
  build_bar_csr();
  pold_ = p_;
  stats.triangles = static_cast<int64_t>(triangles_.size());
  stats.bars = static_cast<int64_t>(bars_.size());
  return stats;
}

void CpuEngine::build_bar_csr() {
  const size_t n = p_.size();
  csr_offset_.assign(n + 1, 0);
  for (const auto& b : bars_) {
    ++csr_offset_[b[0] + 1];
    ++csr_offset_[b[1] + 1];
  }
  for (size_t i = 0; i < n; ++i) csr_offset_[i + 1] += csr_offset_[i];
  csr_entry_.resize(2 * bars_.size());
  std::vector<int32_t> fill(csr_offset_.begin(), csr_offset_.end() - 1);
  for (size_t b = 0; b < bars_.size(); ++b) {
    csr_entry_[fill[bars_[b][0]]++] = static_cast<int32_t>(2 * b);
    csr_entry_[fill[bars_[b][1]]++] = static_cast<int32_t>(2 * b + 1);
  }
}

// ---- Step 4: bar lengths and targets ------------------------------------------------------------

double CpuEngine::measure_bars() {
  const size_t nb = bars_.size();
  bar_length_.resize(nb);
  // A graded field's sizes are evaluated at the bar midpoints once per topology: between two
  // triangulations no node moves more than ttol of its size, so h barely changes, and the
  // evaluation (an ellipse's or a polygon's distance) costs more than the rest of the step.
  const bool measure_size = bar_size_.size() != nb;
  bar_size_.resize(nb);
  const SizeView fh = problem_->size.view();
  const bool uniform = problem_->size.uniform();
  const size_t chunks = ThreadPool::chunk_count(nb, kChunk);
  std::vector<double> sum_l2(chunks, 0.0), sum_h2(chunks, 0.0);
  pool_.for_chunks(nb, kChunk, [&](size_t c, size_t begin, size_t end) {
    double l2 = 0.0, h2 = 0.0;
    for (size_t b = begin; b < end; ++b) {
      const Vec2 a = p_[bars_[b][0]], e = p_[bars_[b][1]];
      const double len = norm(a - e);
      if (measure_size) bar_size_[b] = uniform ? 1.0 : eval_size(fh, 0.5 * (a + e));
      const double h = bar_size_[b];
      bar_length_[b] = len;
      l2 += len * len;
      h2 += h * h;
    }
    sum_l2[c] = l2;
    sum_h2[c] = h2;
  });
  double l2 = 0.0, h2 = 0.0;
  for (size_t c = 0; c < chunks; ++c) {
    l2 += sum_l2[c];
    h2 += sum_h2[c];
  }
  return h2 > 0.0 ? problem_->params.fscale * std::sqrt(l2 / h2) : 0.0;
}

// ---- Step 6: density control -------------------------------------------------------------------

int64_t CpuEngine::remove_crowded_points(int64_t max_removed) {
  const double scale = measure_bars();
  std::vector<char> remove(p_.size(), 0);
  int64_t count = 0;
  for (size_t b = 0; b < bars_.size(); ++b) {
    if (bar_size_[b] * scale <= 2.0 * bar_length_[b]) continue;
    for (int32_t end : bars_[b]) {
      if (end >= nfix_ && !remove[end]) {
        remove[end] = 1;
        ++count;
      }
    }
  }
  if (count > max_removed) return 0;
  if (count > 0) keep_points(remove);
  return count;
}

void CpuEngine::remove_points(const std::vector<int32_t>& indices) {
  std::vector<char> remove(p_.size(), 0);
  for (int32_t i : indices)
    if (i >= nfix_ && i < node_count()) remove[i] = 1;
  keep_points(remove);
}

void CpuEngine::keep_points(const std::vector<char>& remove) {
  size_t out = 0;
  for (size_t i = 0; i < p_.size(); ++i)
    if (!remove[i]) p_[out++] = p_[i];
  p_.resize(out);
  reset_node_state();
}

void CpuEngine::reset_node_state() {
  pold_.assign(p_.size(), Vec2{INFINITY, INFINITY});
  velocity_.assign(p_.size(), Vec2{});
  on_boundary_.assign(p_.size(), 0);
  clearance_.assign(p_.size(), 0.0f);  // unknown: evaluated at the next step
  clearance_rule_ = ClearanceRule::make(problem_->lipschitz, problem_->params.geps * problem_->h0,
                                        kNearBoundaryRelative * problem_->h0, problem_->h0);
  for (int64_t f = 0; f < nfix_; ++f)
    on_boundary_[f] =
        eval_sdf(problem_->geometry.view(), p_[f]) >= -kNearBoundaryRelative * problem_->h0;
  dt_ = {};
  triangles_.clear();
  bars_.clear();
}

// ---- Steps 5, 7, 8: forces, Euler step, projection ---------------------------------------------

StepResult CpuEngine::move_points() {
  const Params& prm = problem_->params;
  const double h0 = problem_->h0, geps = prm.geps * h0, deps = prm.deps * h0;
  const double scale = measure_bars();
  const size_t nb = bars_.size(), n = p_.size();

  // Step 5: repulsive bar forces F = max(L0 - L, 0), along the bar.
  bar_force_.resize(nb);
  pool_.for_chunks(nb, kChunk, [&](size_t, size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const double len = bar_length_[b];
      const double f = std::max(bar_size_[b] * scale - len, 0.0);
      const Vec2 v = p_[bars_[b][0]] - p_[bars_[b][1]];
      bar_force_[b] = len > 0.0 ? (f / len) * v : Vec2{};
    }
  });

  // Each node sums its bars (CSR), moves, and is projected back when it left the domain.
  const ProgramView fd = problem_->geometry.view();
  const size_t chunks = ThreadPool::chunk_count(n, kChunk);
  std::vector<double> chunk_move(chunks, 0.0), chunk_drift(chunks, 0.0), chunk_sq(chunks, 0.0);
  std::vector<int64_t> chunk_interior(chunks, 0);
  pool_.for_chunks(n, kChunk, [&](size_t c, size_t begin, size_t end) {
    double max_move = 0.0, max_drift = 0.0, sq = 0.0;
    int64_t interior = 0;
    for (size_t i = begin; i < end; ++i) {
      if (static_cast<int64_t>(i) < nfix_) continue;  // fixed nodes stay exactly where they are
      Vec2 total{};
      double size_sum = 0.0;
      for (int32_t k = csr_offset_[i]; k < csr_offset_[i + 1]; ++k) {
        const int32_t e = csr_entry_[k];
        const Vec2 f = bar_force_[e >> 1];
        total = (e & 1) ? total - f : total + f;
        size_sum += bar_size_[e >> 1];
      }
      // Moves are measured in the node's own size (step_rule.cuh): h0 * the mean h of its bars.
      const int32_t degree = csr_offset_[i + 1] - csr_offset_[i];
      const double unit = degree > 0 ? h0 * (size_sum / degree) : h0;
      // Heavy-ball momentum: the previous step carries over, scaled (params.h).
      const Vec2 step = prm.deltat * total + prm.momentum * velocity_[i];
      velocity_[i] = step;
      Vec2 q = p_[i] + step;
      // Far enough inside, d's value decides nothing (clearance.cuh): its bound stands in.
      const double inside = clearance_rule_.carried(clearance_[i], norm(step));
      const double d = clearance_rule_.decides(inside) ? -inside : eval_sdf(fd, q);
      clearance_[i] = round_down_to_float(-d);
      if (d > 0.0) q = project_step(fd, q, d, deps);
      on_boundary_[i] = d >= -kNearBoundaryRelative * h0;
      if (d < -geps) {
        const double move = norm(step) / unit;
        sq += move * move;
        max_move = std::max(max_move, move);
        ++interior;
      }
      p_[i] = q;
      max_drift = std::max(max_drift, norm(q - pold_[i]) / unit);
    }
    chunk_move[c] = max_move;
    chunk_drift[c] = max_drift;
    chunk_sq[c] = sq;
    chunk_interior[c] = interior;
  });
  StepResult r;
  double sq = 0.0;
  int64_t interior = 0;
  for (size_t c = 0; c < chunks; ++c) {
    sq += chunk_sq[c];
    interior += chunk_interior[c];
  }
  r.rms_move = interior > 0 ? std::sqrt(sq / interior) : 0.0;
  for (size_t c = 0; c < chunks; ++c) {
    r.max_move = std::max(r.max_move, chunk_move[c]);
    r.max_drift = std::max(r.max_drift, chunk_drift[c]);
  }
  return r;
}

}  // namespace meshd
