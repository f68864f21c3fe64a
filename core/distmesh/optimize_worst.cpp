#include "core/distmesh/optimize_worst.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/common/thread_pool.h"
#include "core/distmesh/node_moves.h"
#include "core/distmesh/pattern_search.h"
#include "core/geometry/projection.cuh"

namespace meshd {
namespace {

constexpr int kPasses = 8;
constexpr int kStepHalvings = 6;

class Optimizer : NodeMoves {
 public:
  Optimizer(const CompiledProblem& problem, std::vector<Vec2>& points,
            const std::vector<std::array<int32_t, 3>>& triangles,
            const std::vector<int32_t>& boundary, ThreadPool* pool)
      : NodeMoves(problem, points, triangles, boundary, pool) {}

  int64_t run(const std::vector<int32_t>* below) {
    // good[t]: t's quality was at least the threshold when last measured and none of its nodes
    // has moved since, so measuring it again would give the same value. Each pass then measures
    // only the few triangles near moved nodes instead of all of them, with the same result.
    std::vector<char> good(t_.size(), below != nullptr ? 1 : 0);
    if (below != nullptr)
      for (int32_t t : *below) good[t] = 0;
    int64_t moves = snap_to_boundary(good);
    for (int pass = 0; pass < kPasses; ++pass) {
      const std::vector<int32_t> nodes = nodes_of_bad_triangles(good);
      stars_.add(nodes);
      int64_t pass_moves = 0;
      // Nodes of one colour share no triangle, so each one's star holds none of the others: they
      // move in parallel, and the result is the same for any number of threads.
      for (const std::vector<int32_t>& group : colour_groups(nodes)) {
        std::vector<char> moved(group.size(), 0);
        for_chunks(pool_, group.size(), kNodesPerChunk, [&](size_t, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) moved[i] = optimize_node(group[i]);
        });
        for (size_t i = 0; i < group.size(); ++i) {
          if (!moved[i]) continue;
          ++pass_moves;
          mark_star(group[i], good);
        }
      }
      moves += pass_moves;
      if (pass_moves == 0) break;
    }
    return moves;
  }

 private:
  // Puts the nodes of the mesh's boundary that lie off the domain's boundary onto it, where
  // their star stays valid. Such a node sags between two neighbours on the boundary that are
  // too far apart for one node at full length and too close for two: next to a concave corner
  // the Delaunay edge across the corner is dropped with its triangle, and the node, pushed
  // inward by both, settles up to half an edge inside.
  int64_t snap_to_boundary(std::vector<char>& good) {
    // Where each node would go (the distance and the projection, the costly part) depends on that
    // node alone: found in parallel. Whether it goes depends on its neighbours: decided in order.
    using Target = std::pair<int32_t, Vec2>;
    const std::vector<Target> targets =
        gather_chunks<Target>(pool_, p_.size() - nfix_, kNodesPerSnapChunk,
                              [&](size_t begin, size_t end, std::vector<Target>& out) {
                                for (size_t i = begin; i < end; ++i) {
                                  const int32_t v = nfix_ + static_cast<int32_t>(i);
                                  if (!on_boundary_[v] || lies_on_boundary(p_[v])) continue;
                                  const Vec2 x = project_to_boundary(fd_, p_[v], deps_);
                                  if (lies_on_boundary(x)) out.push_back({v, x});
                                }
                              });
    std::vector<int32_t> nodes;
    for (const auto& [v, x] : targets) nodes.push_back(v);
    stars_.add(nodes);
    int64_t moves = 0;
    for (const auto& [v, x] : targets) {
      // When the opposite edge of a triangle in v's star lies on the boundary too, the snap
      // flattens that triangle, to a round-off area of either sign that no later move undoes.
      const double before = star_quality(v, p_[v]), after = star_quality(v, x);
      if (after <= 0.0 || after < std::min(before, kSnapMinQuality)) continue;
      if (!star_stays_inside(v, x, 0.0)) continue;
      p_[v] = x;
      mark_star(v, good);
      ++moves;
    }
    return moves;
  }

  // The free nodes, increasing, of the triangles not known to be good that measure under the
  // threshold; the others become good.
  std::vector<int32_t> nodes_of_bad_triangles(std::vector<char>& good) {
    std::vector<int32_t> nodes =
        gather_chunks<int32_t>(pool_, t_.size(), kTrianglesPerChunk,
                               [&](size_t begin, size_t end, std::vector<int32_t>& out) {
                                 for (size_t t = begin; t < end; ++t) {
                                   if (good[t]) continue;
                                   if (quality(static_cast<int32_t>(t)) >= kOptimizeBelowQuality) {
                                     good[t] = 1;
                                     continue;
                                   }
                                   for (int32_t v : t_[t])
                                     if (v >= nfix_) out.push_back(v);
                                 }
                               });
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }

  // v moved: the triangles around it must be measured again.
  void mark_star(int32_t v, std::vector<char>& good) const {
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t) good[*t] = 0;
  }

  // Worst quality in v's star with v at position x.
  double star_quality(int32_t v, Vec2 x) {
    const Vec2 saved = p_[v];
    p_[v] = x;
    double worst = INFINITY;
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t)
      worst = std::min(worst, quality(*t));
    p_[v] = saved;
    return worst;
  }

  double mean_star_edge(int32_t v) const {
    double sum = 0.0;
    int count = 0;
    for (const int32_t* t = stars_.begin(v); t != stars_.end(v); ++t) {
      for (int32_t u : t_[*t]) {
        if (u == v) continue;
        sum += norm(p_[u] - p_[v]);
        ++count;
      }
    }
    return count > 0 ? sum / count : 0.0;
  }

  // Pattern search from v's position; returns whether v moved.
  bool optimize_node(int32_t v) {
    const bool boundary = on_boundary_[v];
    double best = star_quality(v, p_[v]);
    const Vec2 start = p_[v];
    double step = 0.25 * mean_star_edge(v);
    for (int h = 0; h < kStepHalvings; ++h, step *= 0.5) {
      bool improved = true;
      for (int moves = 0; improved && moves < kMovesPerStepLength; ++moves) {
        improved = false;
        Vec2 dirs[8];
        int n_dirs = 0;
        if (boundary) {
          const Vec2 g = sdf_gradient(fd_, p_[v], eval_sdf(fd_, p_[v]), deps_);
          const double len = norm(g);
          if (len <= 0.0) return false;
          dirs[n_dirs++] = {-g.y / len, g.x / len};
          dirs[n_dirs++] = {g.y / len, -g.x / len};
        } else {
          for (int k = 0; k < 8; ++k)
            dirs[n_dirs++] = {std::cos(k * M_PI / 4), std::sin(k * M_PI / 4)};
        }
        Vec2 best_x = p_[v];
        for (int k = 0; k < n_dirs; ++k) {
          Vec2 x = p_[v] + step * dirs[k];
          const double d = boundary ? 0.0 : eval_sdf(fd_, x);
          if (boundary)
            x = project_to_boundary(fd_, x, deps_);
          else if (d >= 0.0)
            continue;
          const double q = star_quality(v, x);
          if (q > best && star_stays_inside(v, x, d)) {
            best = q;
            best_x = x;
            improved = true;
          }
        }
        p_[v] = best_x;
      }
    }
    return !(p_[v] == start);
  }

  // A snap may lower the worst quality in the node's star to this, or to what it was, not below.
  static constexpr double kSnapMinQuality = 0.1;
  // Nodes per task in a parallel loop: a boundary node's search costs a few hundred distances.
  static constexpr size_t kNodesPerChunk = 16;
  static constexpr size_t kNodesPerSnapChunk = 256;
  static constexpr size_t kTrianglesPerChunk = 4096;
};

}  // namespace

int64_t optimize_worst_elements(const CompiledProblem& problem, std::vector<Vec2>& points,
                                const std::vector<std::array<int32_t, 3>>& triangles,
                                const std::vector<int32_t>& boundary,
                                const std::vector<int32_t>* below, ThreadPool* pool) {
  return Optimizer(problem, points, triangles, boundary, pool).run(below);
}

}  // namespace meshd
