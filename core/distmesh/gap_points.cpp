#include "core/distmesh/gap_points.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/common/thread_pool.h"
#include "core/distmesh/initial_points.cuh"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// The rows of grid points that lie within a triangle's vertical extent (possibly empty).
std::pair<int64_t, int64_t> rows_of(const InitialGrid& g, const Vec2 v[3]) {
  const double y_lo = std::min({v[0].y, v[1].y, v[2].y}), y_hi = std::max({v[0].y, v[1].y, v[2].y});
  return {
      std::max<int64_t>(0, static_cast<int64_t>(std::ceil((y_lo - g.origin.y) / g.dy))),
      std::min<int64_t>(g.ny - 1, static_cast<int64_t>(std::floor((y_hi - g.origin.y) / g.dy)))};
}

// Marks the grid points of rows [j0, j1] that lie in the triangle v: on each row, between its
// edges.
void cover_rows(const InitialGrid& g, const Vec2 v[3], int64_t j0, int64_t j1,
                std::vector<char>& covered) {
  for (int64_t j = j0; j <= j1; ++j) {
    const double y = g.origin.y + g.dy * static_cast<double>(j);
    double x_lo = INFINITY, x_hi = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = v[k], b = v[(k + 1) % 3];
      if (y < std::min(a.y, b.y) || y > std::max(a.y, b.y)) continue;
      // A level edge on the row contributes both ends; any other its crossing.
      const double xa = a.y == b.y ? a.x : a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
      const double xb = a.y == b.y ? b.x : xa;
      x_lo = std::min({x_lo, xa, xb});
      x_hi = std::max({x_hi, xa, xb});
    }
    if (!(x_lo <= x_hi)) continue;
    const double shift = (j & 1) ? 0.5 : 0.0;
    const int64_t i0 =
        std::max<int64_t>(0, static_cast<int64_t>(std::ceil((x_lo - g.origin.x) / g.dx - shift)));
    const int64_t i1 = std::min<int64_t>(
        g.nx - 1, static_cast<int64_t>(std::floor((x_hi - g.origin.x) / g.dx - shift)));
    for (int64_t i = i0; i <= i1; ++i) covered[static_cast<size_t>(j * g.nx + i)] = 1;
  }
}

// Which grid points lie in some triangle. The rows go in bands, one task a band, each with the
// triangles that reach into it, so that tasks write disjoint rows.
std::vector<char> covered_grid_points(const InitialGrid& g, const std::vector<Vec2>& p,
                                      const std::vector<std::array<int32_t, 3>>& triangles,
                                      ThreadPool* pool) {
  constexpr int64_t kRowsPerBand = 32;
  const int64_t bands = (g.ny + kRowsPerBand - 1) / kRowsPerBand;
  std::vector<int64_t> start(static_cast<size_t>(bands + 1), 0);
  auto band_range = [&](const std::array<int32_t, 3>& t) {
    const Vec2 v[3] = {p[t[0]], p[t[1]], p[t[2]]};
    const auto [j0, j1] = rows_of(g, v);
    return std::pair<int64_t, int64_t>{j0 / kRowsPerBand, j1 < j0 ? -1 : j1 / kRowsPerBand};
  };
  for (const auto& t : triangles) {
    const auto [b0, b1] = band_range(t);
    for (int64_t b = b0; b <= b1; ++b) ++start[static_cast<size_t>(b + 1)];
  }
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<int32_t> in_band(static_cast<size_t>(start.back()));
  std::vector<int64_t> fill(start.begin(), start.end() - 1);
  for (size_t k = 0; k < triangles.size(); ++k) {
    const auto [b0, b1] = band_range(triangles[k]);
    for (int64_t b = b0; b <= b1; ++b)
      in_band[static_cast<size_t>(fill[static_cast<size_t>(b)]++)] = static_cast<int32_t>(k);
  }
  std::vector<char> covered(static_cast<size_t>(g.nx * g.ny), 0);
  for_chunks(pool, static_cast<size_t>(bands), 1, [&](size_t, size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const int64_t first = static_cast<int64_t>(b) * kRowsPerBand;
      const int64_t last = std::min(g.ny - 1, first + kRowsPerBand - 1);
      for (int64_t e = start[b]; e < start[b + 1]; ++e) {
        const auto& t = triangles[static_cast<size_t>(in_band[static_cast<size_t>(e)])];
        const Vec2 v[3] = {p[t[0]], p[t[1]], p[t[2]]};
        const auto [j0, j1] = rows_of(g, v);
        cover_rows(g, v, std::max(j0, first), std::min(j1, last), covered);
      }
    }
  });
  return covered;
}

// The nodes in square buckets, for the question whether any lies within a radius of a point.
class NodeBuckets {
 public:
  NodeBuckets(const std::vector<Vec2>& nodes, const Box& box, double cell)
      : nodes_(nodes), origin_(box.min), cell_(cell) {
    nx_ = std::max<int64_t>(1, static_cast<int64_t>((box.max.x - box.min.x) / cell) + 1);
    ny_ = std::max<int64_t>(1, static_cast<int64_t>((box.max.y - box.min.y) / cell) + 1);
    std::vector<int64_t> bucket(nodes.size());
    start_.assign(static_cast<size_t>(nx_ * ny_ + 1), 0);
    for (size_t k = 0; k < nodes.size(); ++k) {
      bucket[k] = index(column(nodes[k].x), row(nodes[k].y));
      ++start_[static_cast<size_t>(bucket[k] + 1)];
    }
    for (size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    entries_.resize(nodes.size());
    std::vector<int64_t> fill(start_.begin(), start_.end() - 1);
    for (size_t k = 0; k < nodes.size(); ++k)
      entries_[static_cast<size_t>(fill[static_cast<size_t>(bucket[k])]++)] =
          static_cast<int32_t>(k);
  }

  bool any_within(Vec2 q, double radius) const {
    const int64_t i0 = column(q.x - radius), i1 = column(q.x + radius);
    const int64_t j0 = row(q.y - radius), j1 = row(q.y + radius);
    for (int64_t j = j0; j <= j1; ++j)
      for (int64_t i = i0; i <= i1; ++i) {
        const auto b = static_cast<size_t>(index(i, j));
        for (int64_t e = start_[b]; e < start_[b + 1]; ++e)
          if (norm(nodes_[static_cast<size_t>(entries_[static_cast<size_t>(e)])] - q) < radius)
            return true;
      }
    return false;
  }

 private:
  int64_t column(double x) const {
    return std::clamp<int64_t>(static_cast<int64_t>(std::floor((x - origin_.x) / cell_)), 0,
                               nx_ - 1);
  }
  int64_t row(double y) const {
    return std::clamp<int64_t>(static_cast<int64_t>(std::floor((y - origin_.y) / cell_)), 0,
                               ny_ - 1);
  }
  int64_t index(int64_t i, int64_t j) const { return j * nx_ + i; }

  const std::vector<Vec2>& nodes_;
  Vec2 origin_;
  double cell_;
  int64_t nx_ = 1, ny_ = 1;
  std::vector<int64_t> start_;
  std::vector<int32_t> entries_;
};

}  // namespace

std::vector<Vec2> uncovered_grid_points(const CompiledProblem& level,
                                        const std::vector<Vec2>& coarse_points,
                                        const std::vector<std::array<int32_t, 3>>& coarse_triangles,
                                        ThreadPool* pool) {
  const InitialGrid grid = make_initial_grid(level.bbox, level.h0);
  const std::vector<char> covered =
      covered_grid_points(grid, coarse_points, coarse_triangles, pool);
  const ProgramView fd = level.geometry.view();
  const SizeView fh = level.size.view();
  const double geps = level.params.geps * level.h0;
  // The sizes' floor is 1: compile_problem folds the field's lower bound into h0.
  constexpr double kSizeFloor = 1.0;
  // The distance and the size run only at the grid points no triangle covers: the parts outside
  // the domain, and the gaps. Outside, at distance d, the next d / (L dx) points of the row lie
  // outside too (the distance changes by at most L per unit): skipped, so that a hole or the
  // land of a coastline costs a few evaluations a row.
  const double skip_per_outside = 1.0 / (level.lipschitz * grid.dx);
  constexpr size_t kChunk = 1 << 16;
  return gather_chunks<Vec2>(
      pool, static_cast<size_t>(grid.nx * grid.ny), kChunk,
      [&](size_t begin, size_t end, std::vector<Vec2>& out) {
        for (size_t k = begin; k < end; ++k) {
          if (covered[k]) continue;
          const auto index = static_cast<int64_t>(k);
          const Vec2 q = initial_grid_point(grid, index);
          const double d = eval_sdf(fd, q);
          if (!(d < -geps)) {
            const double skip = d * skip_per_outside;
            if (skip >= 1.0) {
              const auto row_last = static_cast<size_t>((index / grid.nx + 1) * grid.nx - 1);
              k = std::min({k + static_cast<size_t>(std::min(skip, 1e15)), row_last, end - 1});
            }
            continue;
          }
          if (!keep_by_size(level.seed, grid, index, eval_size(fh, q), kSizeFloor)) continue;
          out.push_back(q);
        }
      });
}

std::vector<Vec2> away_from_nodes(const CompiledProblem& level, const std::vector<Vec2>& points,
                                  const std::vector<Vec2>& nodes) {
  if (points.empty()) return {};
  // Two edges a bucket keep the buckets few where the level is fine and the scans short where
  // it is coarse.
  const NodeBuckets buckets(nodes, level.bbox, 2 * level.h0);
  const SizeView fh = level.size.view();
  std::vector<Vec2> away;
  for (const Vec2& q : points)
    if (!buckets.any_within(q, 0.5 * level.h0 * eval_size(fh, q))) away.push_back(q);
  return away;
}

}  // namespace meshd
