#include "core/distmesh/smooth_mean_quality.h"

#include <algorithm>

#include "core/common/thread_pool.h"
#include "core/distmesh/node_moves.h"
#include "core/distmesh/optimize_worst.h"
#include "core/geometry/projection.cuh"

namespace meshd {
namespace {

// The first sweep gains most; the third about a tenth of the first (a coastline, G5).
constexpr int kSweeps = 3;

class Smoother : NodeMoves {
 public:
  Smoother(const CompiledProblem& problem, std::vector<Vec2>& points,
           const std::vector<std::array<int32_t, 3>>& triangles,
           const std::vector<int32_t>& boundary, ThreadPool* pool)
      : NodeMoves(problem, points, triangles, boundary, pool) {}

  int64_t run() {
    int64_t moves = 0;
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
      const std::vector<int32_t> nodes = nodes_to_smooth();
      stars_.add(nodes);
      int64_t sweep_moves = 0;
      for (const std::vector<int32_t>& group : colour_groups(nodes)) {
        std::vector<char> moved(group.size(), 0);
        for_chunks(pool_, group.size(), kNodesPerChunk, [&](size_t, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) moved[i] = smooth_node(group[i]);
        });
        sweep_moves += std::count(moved.begin(), moved.end(), 1);
      }
      moves += sweep_moves;
      if (sweep_moves == 0) break;
    }
    return moves;
  }

 private:
  // The free nodes, increasing, of the triangles under kSmoothBelowQuality, without the nodes of
  // triangles under kOptimizeBelowQuality.
  std::vector<int32_t> nodes_to_smooth() const {
    // Each triangle names its free nodes as +v + 1 (to smooth) or -(v + 1) (left alone).
    std::vector<int32_t> marks =
        gather_chunks<int32_t>(pool_, t_.size(), kTrianglesPerChunk,
                               [&](size_t begin, size_t end, std::vector<int32_t>& out) {
                                 for (size_t t = begin; t < end; ++t) {
                                   const double q = quality(static_cast<int32_t>(t));
                                   if (q >= kSmoothBelowQuality) continue;
                                   const int32_t sign = q < kOptimizeBelowQuality ? -1 : 1;
                                   for (int32_t v : t_[t])
                                     if (v >= nfix_) out.push_back(sign * (v + 1));
                                 }
                               });
    std::vector<char> left_alone(p_.size(), 0);
    for (int32_t m : marks)
      if (m < 0) left_alone[-m - 1] = 1;
    std::vector<int32_t> nodes;
    for (int32_t m : marks)
      if (m > 0 && !left_alone[m - 1]) nodes.push_back(m - 1);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }

  // The sum of the qualities in v's star, or -1 where one is under kOptimizeBelowQuality.
  double star_sum(int32_t v) const {
    double sum = 0.0;
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t) {
      const double q = quality(*t);
      if (q < kOptimizeBelowQuality) return -1.0;
      sum += q;
    }
    return sum;
  }

  // Moves v to its neighbours' mean (onto the boundary, for a boundary node) where its star's
  // sum of qualities rises and none falls under the threshold; returns whether it moved.
  bool smooth_node(int32_t v) {
    const double before = star_sum(v);
    if (before < 0.0) return false;
    // Each neighbour of an interior node is a corner of two of its triangles.
    Vec2 sum{0.0, 0.0};
    int count = 0;
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t)
      for (int32_t u : t_[*t])
        if (u != v) {
          sum = sum + p_[u];
          ++count;
        }
    if (count == 0) return false;
    Vec2 x = (1.0 / count) * sum;
    if (on_boundary_[v]) x = project_to_boundary(fd_, x, deps_);
    const Vec2 start = p_[v];
    p_[v] = x;
    const double after = star_sum(v);
    bool keep = after > before;
    if (keep) {
      const double d = on_boundary_[v] ? 0.0 : eval_sdf(fd_, x);
      keep = (on_boundary_[v] ? lies_on_boundary(x) : d < 0.0) && star_stays_inside(v, x, d);
    }
    if (!keep) p_[v] = start;
    return keep;
  }

  static constexpr size_t kNodesPerChunk = 64;
  static constexpr size_t kTrianglesPerChunk = 4096;
};

}  // namespace

int64_t smooth_mean_quality(const CompiledProblem& problem, std::vector<Vec2>& points,
                            const std::vector<std::array<int32_t, 3>>& triangles,
                            const std::vector<int32_t>& boundary, ThreadPool* pool) {
  return Smoother(problem, points, triangles, boundary, pool).run();
}

}  // namespace meshd
