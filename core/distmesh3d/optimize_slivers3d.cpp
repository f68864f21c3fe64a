#include "core/distmesh3d/optimize_slivers3d.h"

#include <algorithm>
#include <cmath>

#include "core/distmesh/pattern_search.h"
#include "core/distmesh3d/projection3d.h"
#include "core/mesh3d/tet_boundary.h"
#include "core/mesh3d/tet_quality.cuh"
#include "core/mesh3d/tet_stars.h"

namespace meshd {
namespace {

// Four passes take most of what eight did for half the time: on 2 cores the fifth to eighth
// moved ever fewer nodes (a tenth of those visited by the eighth) and gave the ball and the cube
// minus a ball at 10k and 100k nodes the same mean and a worst element 0.02 higher (0.52-0.59
// against 0.50-0.57), for 35-45% of the finish's time.
constexpr int kPasses = 4;
constexpr int kStepHalvings = 6;
// Nodes per task in a parallel loop: a boundary node's search costs a few hundred distances.
constexpr size_t kNodesPerChunk = 16;
constexpr size_t kTetsPerChunk = 4096;

// The 14 directions of a body-centred lattice's neighbours: the axes and the cube's diagonals.
std::array<Vec3, 14> space_directions() {
  std::array<Vec3, 14> d{};
  int n = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0}) {
      Vec3 v{};
      (axis == 0 ? v.x : axis == 1 ? v.y : v.z) = s;
      d[n++] = v;
    }
  const double c = 1.0 / std::sqrt(3.0);
  for (int k = 0; k < 8; ++k) d[n++] = {k & 1 ? c : -c, k & 2 ? c : -c, k & 4 ? c : -c};
  return d;
}

class SliverOptimizer {
 public:
  SliverOptimizer(const Domain3& domain, double step, std::vector<Vec3>& points,
                  const std::vector<std::array<int32_t, 4>>& tets, int64_t fixed, ThreadPool* pool)
      : domain_(domain),
        step_(step),
        p_(points),
        t_(tets),
        fixed_(fixed),
        pool_(pool),
        on_boundary_(points.size(), 0),
        stars_(points.size(), tets) {
    for (const auto& f : tet_boundary_faces(tets))
      for (int32_t v : f) on_boundary_[v] = 1;
  }

  int64_t run() {
    int64_t moves = 0;
    for (int pass = 0; pass < kPasses; ++pass) {
      int64_t pass_moves = 0;
      for (const std::vector<int32_t>& group : colour_groups(nodes_of_bad_tets())) {
        std::vector<char> moved(group.size(), 0);
        for_chunks(pool_, group.size(), kNodesPerChunk, [&](size_t, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) moved[i] = optimize_node(group[i]);
        });
        for (char m : moved) pass_moves += m;
      }
      moves += pass_moves;
      if (pass_moves == 0) break;
    }
    return moves;
  }

 private:
  double quality(int32_t t) const {
    const auto& v = t_[t];
    return oriented_tet_radius_ratio(p_[v[0]], p_[v[1]], p_[v[2]], p_[v[3]]);
  }

  // The free nodes, increasing, of the tetrahedra worth visiting.
  std::vector<int32_t> nodes_of_bad_tets() const {
    std::vector<int32_t> nodes = gather_chunks<int32_t>(
        pool_, t_.size(), kTetsPerChunk, [&](size_t begin, size_t end, std::vector<int32_t>& out) {
          for (size_t t = begin; t < end; ++t) {
            if (quality(static_cast<int32_t>(t)) >= kVisitBelowQuality3) continue;
            for (int32_t v : t_[t])
              if (v >= fixed_) out.push_back(v);
          }
        });
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }

  std::vector<std::vector<int32_t>> colour_groups(const std::vector<int32_t>& nodes) const {
    return stars_.colour_groups(nodes, t_);
  }

  // How good v's star is with v at x: its worst quality up to the target, then its mean.
  struct Score {
    double worst = -INFINITY;
    double mean = -INFINITY;
    bool operator>(const Score& o) const {
      return worst > o.worst || (worst == o.worst && mean > o.mean);
    }
  };
  // Stops as soon as its worst falls under `give_up_below` (the best so far, which it then
  // cannot beat): most candidates of a search lose at their first poor tetrahedron.
  Score star_score(int32_t v, Vec3 x, double give_up_below = -INFINITY) {
    const Vec3 saved = p_[v];
    p_[v] = x;
    double worst = INFINITY, sum = 0.0;
    for (int64_t k = stars_.first[v]; k < stars_.first[v + 1] && !(worst < give_up_below); ++k) {
      const double q = quality(stars_.tets[k]);
      worst = std::min(worst, q);
      sum += q;
    }
    p_[v] = saved;
    const auto count = static_cast<double>(stars_.size(v));
    return {std::min(worst, kOptimizeBelowQuality3), count > 0.0 ? sum / count : 0.0};
  }

  // Pattern search from v's position; returns whether v moved.
  bool optimize_node(int32_t v) {
    static const std::array<Vec3, 14> kSpace = space_directions();
    const bool boundary = on_boundary_[v];
    Score best = star_score(v, p_[v]);
    const Vec3 start = p_[v];
    double length = 0.25 * stars_.mean_edge(v, p_, t_);
    for (int h = 0; h < kStepHalvings; ++h, length *= 0.5) {
      bool improved = true;
      for (int moves = 0; improved && moves < kMovesPerStepLength; ++moves) {
        improved = false;
        Vec3 dirs[14];
        int n_dirs = 0;
        if (boundary) {
          n_dirs = boundary_tangents3d(domain_, p_[v], step_, dirs);
          if (n_dirs == 0) return !(p_[v] == start);
        } else {
          for (const Vec3& d : kSpace) dirs[n_dirs++] = d;
        }
        Vec3 best_x = p_[v];
        for (int k = 0; k < n_dirs; ++k) {
          Vec3 x = p_[v] + length * dirs[k];
          if (boundary)
            x = project_to_boundary3d(domain_, x, step_);
          else if (domain_.distance(x) >= 0.0)
            continue;
          const Score q = star_score(v, x, best.worst);
          if (q > best) {
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

  const Domain3& domain_;
  double step_;
  std::vector<Vec3>& p_;
  const std::vector<std::array<int32_t, 4>>& t_;
  int64_t fixed_;
  ThreadPool* pool_;
  std::vector<char> on_boundary_;
  TetStars stars_;
};

}  // namespace

int64_t optimize_slivers3d(const Domain3& domain, double step, std::vector<Vec3>& points,
                           const std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                           ThreadPool* pool) {
  return SliverOptimizer(domain, step, points, tets, fixed, pool).run();
}

}  // namespace meshd
