#include "core/distmesh3d/settle_surface3d.h"

#include <algorithm>
#include <cmath>

#include "core/distmesh3d/projection3d.h"
#include "core/mesh3d/tet_boundary.h"
#include "core/mesh3d/tet_quality.cuh"
#include "core/mesh3d/tet_stars.h"

namespace meshd {
namespace {

// Nodes per task: a node costs a few projections and its star's qualities.
constexpr size_t kNodesPerChunk = 32;
// A stuck node may move once its neighbours have: rounds while some move.
constexpr int kRounds = 4;

class SurfaceSettler {
 public:
  SurfaceSettler(const Domain3& domain, double step, std::vector<Vec3>& points,
                 const std::vector<std::array<int32_t, 4>>& tets)
      : domain_(domain),
        step_(step),
        p_(points),
        t_(tets),
        on_surface_(points.size(), 0),
        stars_(points.size(), tets),
        drop_(tets.size(), 0) {
    for (const auto& f : tet_boundary_faces(tets))
      for (int32_t v : f) on_surface_[v] = 1;
  }

  bool on_surface(int32_t v) const { return on_surface_[v] != 0; }
  const std::vector<char>& dropped() const { return drop_; }

  std::vector<std::vector<int32_t>> colour_groups(const std::vector<int32_t>& nodes) const {
    return stars_.colour_groups(nodes, t_);
  }

  // Moves v onto the boundary; returns the caps dropped, or -1 where v stays. Touches only v's
  // star, so nodes that share no tetrahedron settle at once.
  int settle(int32_t v) {
    const double offset = std::fabs(domain_.distance(p_[v]));
    const auto fits = [&](Vec3 x) {
      return std::fabs(domain_.distance(x)) < offset ? outcome(v, x) : Outcome{};
    };
    const Vec3 nearest = project_to_boundary3d(domain_, p_[v], step_);
    Vec3 to = nearest;
    Outcome best = fits(to);
    if (!best.fits()) {
      to = project_to_boundary3d(domain_, surface_ring_centre(v), step_);
      best = fits(to);
    }
    if (!best.fits()) {
      // A search on the boundary around the nearest point: the best place that fits.
      Vec3 dirs[8];
      const int n = boundary_tangents3d(domain_, nearest, step_, dirs);
      const double edge = stars_.mean_edge(v, p_, t_);
      for (double f : {0.1, 0.2, 0.4})
        for (int k = 0; k < n; ++k) {
          const Vec3 x = project_to_boundary3d(domain_, nearest + f * edge * dirs[k], step_);
          const Outcome o = fits(x);
          if (o.worst > best.worst) {
            best = o;
            to = x;
          }
        }
    }
    if (!best.fits()) return -1;
    stars_.for_each(v, [&](int32_t t) {
      if (!drop_[t] && is_cap(t) && quality_with(t, v, to) < kCapQuality) drop_[t] = 1;
    });
    p_[v] = to;
    return best.caps;
  }

 private:
  double quality_with(int32_t t, int32_t v, Vec3 x) const {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k) q[k] = t_[t][k] == v ? x : p_[t_[t][k]];
    return oriented_tet_radius_ratio(q[0], q[1], q[2], q[3]);
  }

  bool is_cap(int32_t t) const {
    for (int32_t u : t_[t])
      if (!on_surface_[u]) return false;
    return true;
  }

  // What moving v to x would do: the caps it drops, and the worst of the tetrahedra that stay.
  struct Outcome {
    int caps = 0;
    double worst = -INFINITY;
    bool fits() const { return worst > 0.0; }
  };
  Outcome outcome(int32_t v, Vec3 x) const {
    Outcome o;
    o.worst = INFINITY;
    stars_.for_each(v, [&](int32_t t) {
      if (drop_[t]) return;
      const double q = quality_with(t, v, x);
      if (is_cap(t) && q < kCapQuality)
        ++o.caps;
      else
        o.worst = std::min(o.worst, q);
    });
    return o;
  }

  // The mean of the surface nodes that share a kept tetrahedron with v.
  Vec3 surface_ring_centre(int32_t v) const {
    Vec3 sum{};
    int count = 0;
    stars_.for_each(v, [&](int32_t t) {
      if (drop_[t]) return;
      for (int32_t u : t_[t])
        if (u != v && on_surface_[u]) {
          sum = sum + p_[u];
          ++count;
        }
    });
    return count > 0 ? (1.0 / count) * sum : p_[v];
  }

  const Domain3& domain_;
  double step_;
  std::vector<Vec3>& p_;
  const std::vector<std::array<int32_t, 4>>& t_;
  std::vector<char> on_surface_;
  TetStars stars_;
  std::vector<char> drop_;
};

// One round over the surface nodes off the boundary; the caps it drops leave `tets`.
SurfaceSettling settle_round(const Domain3& domain, double step, std::vector<Vec3>& points,
                             std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                             ThreadPool* pool) {
  SurfaceSettler settler(domain, step, points, tets);
  // Off the boundary: farther than the gradient's step, far below any tolerance on it.
  std::vector<int32_t> off;
  for (auto v = static_cast<int32_t>(fixed); v < static_cast<int32_t>(points.size()); ++v)
    if (settler.on_surface(v) && std::fabs(domain.distance(points[v])) > step) off.push_back(v);
  SurfaceSettling out;
  for (const std::vector<int32_t>& group : settler.colour_groups(off)) {
    std::vector<int> caps(group.size(), -1);
    for_chunks(pool, group.size(), kNodesPerChunk, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) caps[i] = settler.settle(group[i]);
    });
    for (int c : caps) {
      if (c < 0) {
        ++out.stuck;
        continue;
      }
      ++out.moved;
      out.dropped += c;
    }
  }
  if (out.dropped > 0) {
    std::vector<std::array<int32_t, 4>> kept;
    kept.reserve(tets.size() - out.dropped);
    for (size_t t = 0; t < tets.size(); ++t)
      if (!settler.dropped()[t]) kept.push_back(tets[t]);
    tets = std::move(kept);
  }
  return out;
}

}  // namespace

SurfaceSettling settle_surface3d(const Domain3& domain, double step, std::vector<Vec3>& points,
                                 std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                                 ThreadPool* pool) {
  SurfaceSettling total;
  for (int round = 0; round < kRounds; ++round) {
    const SurfaceSettling r = settle_round(domain, step, points, tets, fixed, pool);
    total.moved += r.moved;
    total.dropped += r.dropped;
    total.stuck = r.stuck;
    if (r.stuck == 0 || r.moved == 0) break;
  }
  return total;
}

}  // namespace meshd
