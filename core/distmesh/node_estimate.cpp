#include "core/distmesh/node_estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// The midpoint rule on a coarse grid of cells (up to 100 x 100, fewer when the distance is
// expensive: long polygons), then each cell where that rule errs is resampled on a kRefine x
// kRefine grid: cells that the boundary may cross, and cells whose 1/h^2 differs from a
// neighbour's by more than kSizeStep. Interior cells of a uniform field are exact at one sample,
// so this reaches the accuracy of a uniform 400 x 400 grid with several times fewer samples (a
// 1,000-node job spent 1.4 ms of its 8 ms on that grid) and at most its cost.
constexpr double kMaxCells = 100.0 * 100.0;
constexpr double kMinCells = 16.0 * 16.0;
constexpr int kRefine = 4;
constexpr double kSizeStep = 1.1;
constexpr double kWorkBudget = 2e7;  // program parameters read, summed over samples

struct CoarseCell {
  double distance;        // at the centre
  double inverse_square;  // 1 / h^2 at the centre, 0 outside the domain
};

// Cells per piece of work: some 30 microseconds of cheap geometry, hundreds for a long polygon.
constexpr size_t kCellsPerChunk = 256;
constexpr size_t kRefinedPerChunk = 32;
constexpr size_t kRefinedPerBlock = 512;  // 64 kB of terms
// Less work than this, on one thread, runs on the caller's thread alone: waking the pool's
// threads for it cost a busy host more than it saved (5% of a GPU host's small-job throughput).
constexpr double kSpreadSeconds = 1e-3;
constexpr size_t kSubcells = kRefine * kRefine;

struct Integral {
  double inverse_size = 0.0;  // integral over the domain of 1 / h(p)^2 dA
  double depth = 0.0;         // the greatest -distance over the samples inside
};

Integral integrate_inverse_size(const CompiledProblem& c, ThreadPool* pool) {
  const double w = c.bbox.max.x - c.bbox.min.x, hgt = c.bbox.max.y - c.bbox.min.y;
  if (!(w > 0 && hgt > 0 && std::isfinite(w) && std::isfinite(hgt))) {
    std::ostringstream box;
    box << "[" << c.bbox.min.x << ", " << c.bbox.max.x << "] x [" << c.bbox.min.y << ", "
        << c.bbox.max.y << "]";
    throw_invalid("geometry", "the domain's box (clipped to bbox when one is given) is " +
                                  box.str() + "; its width and height must be finite and > 0");
  }
  const double cost = static_cast<double>(c.geometry.params.size() + c.size.shapes.params.size());
  const double budget =
      std::clamp(kWorkBudget / (kRefine * kRefine) / std::max(cost, 1.0), kMinCells, kMaxCells);
  // Columns from the box's aspect, rows from what is left of the budget, so that nx * ny stays
  // within `budget` + nx whatever the box: sqrt(w) / sqrt(h), which neither overflows near the
  // double range nor underflows for a box of denormal size (a 1e-323 box gave a 0 cell, 1e4 x
  // 1e4 cells and 1.8 GB); a box far longer than wide (a 2.8e14 x 2 rectangle gave 4.7e9
  // columns) gets `budget` columns and one row.
  const double aspect = std::sqrt(w) / std::sqrt(hgt);
  const int nx = static_cast<int>(std::clamp(std::ceil(std::sqrt(budget) * aspect), 1.0, budget));
  const int ny = static_cast<int>(std::clamp(std::ceil(budget / nx), 1.0, budget));
  const double dx = w / nx, dy = hgt / ny;
  const size_t cells = static_cast<size_t>(nx) * ny;
  const auto sample = [&](double x, double y, double& depth) {
    const Vec2 p{x, y};
    const double d = eval_sdf(c.geometry.view(), p);
    depth = std::max(depth, -d);
    const double h = d < 0.0 ? eval_size(c.size.view(), p) : 0.0;
    return CoarseCell{d, d < 0.0 ? 1.0 / (h * h) : 0.0};
  };
  // Each piece of work keeps its own deepest sample; the greatest of them is the same in any
  // order.
  Integral out;
  const auto keep_deepest = [&](const std::vector<double>& depths) {
    for (double d : depths) out.depth = std::max(out.depth, d);
  };

  // The first piece runs on the caller's thread, timed: the pieces after it go to the pool only
  // where they would take more than kSpreadSeconds here.
  const auto spread = [&](double seconds) { return seconds > kSpreadSeconds ? pool : nullptr; };
  std::vector<CoarseCell> coarse(cells);
  std::vector<double> depths(ThreadPool::chunk_count(cells, kCellsPerChunk), 0.0);
  const auto coarse_piece = [&](size_t piece, size_t begin, size_t end) {
    double depth = 0.0;
    int i = static_cast<int>(begin % nx), j = static_cast<int>(begin / nx);
    for (size_t k = begin; k < end; ++k) {
      coarse[k] = sample(c.bbox.min.x + (i + 0.5) * dx, c.bbox.min.y + (j + 0.5) * dy, depth);
      if (++i == nx) i = 0, ++j;
    }
    depths[piece] = depth;
  };
  const size_t timed = std::min(cells, kCellsPerChunk);
  const auto t0 = std::chrono::steady_clock::now();
  coarse_piece(0, 0, timed);
  const double sample_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
      static_cast<double>(timed);
  for_chunks(spread(sample_seconds * static_cast<double>(cells - timed)), cells - timed,
             kCellsPerChunk, [&](size_t piece, size_t begin, size_t end) {
               coarse_piece(piece + 1, timed + begin, timed + end);
             });
  keep_deepest(depths);

  // The CSG distances never overstate the distance to the boundary: a cell whose centre lies
  // farther from it than half the cell's diagonal is wholly inside or outside.
  const double reach = 0.5 * std::hypot(dx, dy);
  const auto size_changes = [&](const CoarseCell& a, int i, int j) {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return false;
    const CoarseCell& b = coarse[static_cast<size_t>(j) * nx + i];
    if (b.inverse_square == 0.0) return false;
    const double ratio = a.inverse_square / b.inverse_square;
    return ratio > kSizeStep || ratio < 1.0 / kSizeStep;
  };
  std::vector<size_t> refined;  // cells resampled on the fine grid, increasing
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const size_t k = static_cast<size_t>(j) * nx + i;
      const CoarseCell& a = coarse[k];
      const bool boundary = std::fabs(a.distance) <= reach;
      const bool inside = a.inverse_square > 0.0;
      if (boundary || (inside && (size_changes(a, i - 1, j) || size_changes(a, i + 1, j) ||
                                  size_changes(a, i, j - 1) || size_changes(a, i, j + 1))))
        refined.push_back(k);
    }
  }

  // The terms add up in one order, cell by cell, so that the sum has the same bits on any
  // number of threads: a block of refined cells is sampled over the threads, then its terms and
  // the coarse ones before it join the sum, then the next block (one small buffer: a buffer for
  // all the fine terms, 1.3 MB, cost more in page faults than its samples).
  const double sub_x = dx / kRefine, sub_y = dy / kRefine;
  std::vector<double> fine(std::min(refined.size(), kRefinedPerBlock) * kSubcells);
  ThreadPool* const fine_pool =
      spread(sample_seconds * static_cast<double>(refined.size() * kSubcells));
  double& sum = out.inverse_size;
  size_t next = 0;  // the first coarse cell not yet in the sum
  for (size_t first = 0; first < refined.size(); first += kRefinedPerBlock) {
    const size_t count = std::min(kRefinedPerBlock, refined.size() - first);
    depths.assign(ThreadPool::chunk_count(count, kRefinedPerChunk), 0.0);
    for_chunks(fine_pool, count, kRefinedPerChunk, [&](size_t piece, size_t begin, size_t end) {
      double depth = 0.0;
      for (size_t r = begin; r < end; ++r) {
        const size_t cell = refined[first + r];
        const int i = static_cast<int>(cell % nx), j = static_cast<int>(cell / nx);
        const double x0 = c.bbox.min.x + i * dx, y0 = c.bbox.min.y + j * dy;
        double* terms = &fine[r * kSubcells];
        for (int v = 0; v < kRefine; ++v)
          for (int u = 0; u < kRefine; ++u)
            *terms++ =
                sample(x0 + (u + 0.5) * sub_x, y0 + (v + 0.5) * sub_y, depth).inverse_square *
                sub_x * sub_y;
      }
      depths[piece] = depth;
    });
    keep_deepest(depths);
    for (size_t r = 0; r < count; ++r) {
      const size_t cell = refined[first + r];
      for (; next < cell; ++next) sum += coarse[next].inverse_square * dx * dy;
      for (size_t t = 0; t < kSubcells; ++t) sum += fine[r * kSubcells + t];
      next = cell + 1;
    }
  }
  for (; next < cells; ++next) sum += coarse[next].inverse_square * dx * dy;
  return out;
}

double nodes_from_integral(double inverse_size, double h0) {
  return 2.0 / std::sqrt(3.0) * inverse_size / (h0 * h0);
}

}  // namespace

DomainSurvey survey_domain(const CompiledProblem& problem, ThreadPool* pool) {
  const Integral integral = integrate_inverse_size(problem, pool);
  if (integral.inverse_size <= 0.0)
    throw_invalid("geometry", "the domain is empty or thinner than its box / 400");
  return {nodes_from_integral(integral.inverse_size, problem.h0), integral.depth,
          integral.inverse_size};
}

double estimate_node_count(const CompiledProblem& problem, ThreadPool* pool) {
  if (problem.inverse_size_integral > 0.0)
    return nodes_from_integral(problem.inverse_size_integral, problem.h0);
  return survey_domain(problem, pool).nodes;
}

double estimate_node_count(const Problem& problem) {
  return estimate_node_count(compile_problem(problem));
}

double h0_for_node_count(const Problem& problem, double nodes) {
  return problem.h0 * std::sqrt(estimate_node_count(problem) / nodes);
}

}  // namespace meshd
