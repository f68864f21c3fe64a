#include "core/distmesh3d/settle_surface3d.h"

#include <algorithm>
#include <cmath>

#include "core/distmesh3d/projection3d.h"
#include "core/mesh3d/tet_boundary.h"
#include "core/mesh3d/tet_quality.cuh"
#include "core/mesh3d/tet_stars.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// Nodes per task: a node costs a few projections and its star's qualities.
constexpr size_t kNodesPerChunk = 32;
// A stuck node may move once its neighbours have: rounds while some move.
constexpr int kRounds = 4;
// settle_pushing: rounds of pushes, and the quality a pushed tetrahedron must reach.
constexpr int kPushRounds = 3;
constexpr double kPushedQuality = 0.02;

class SurfaceSettler {
 public:
  SurfaceSettler(const Domain3& domain, double step, std::vector<Vec3>& points,
                 const std::vector<std::array<int32_t, 4>>& tets, int64_t fixed)
      : domain_(domain),
        step_(step),
        p_(points),
        t_(tets),
        fixed_(fixed),
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
    return move_to(v, to);
  }

  // For a node that settle left where it was: a few tetrahedra of its star lay flat or turned
  // over at every place tried, each over a face of interior nodes that the nearest point lies
  // on or beyond (two mirror-image tetrahedra of a lattice-like corner of the cube minus a ball,
  // each 0.001 short of flat, left a node 0.53 h0 inside). Those interior nodes step away from
  // the face, along the gradient of the tetrahedron's volume, by the least of a few lengths that
  // keeps their own stars positive, until every tetrahedron fits with v at the nearest point;
  // otherwise all goes back. Moves nodes outside v's star: run on one thread.
  int settle_pushing(int32_t v) {
    const double offset = std::fabs(domain_.distance(p_[v]));
    const Vec3 to = project_to_boundary3d(domain_, p_[v], step_);
    if (!(std::fabs(domain_.distance(to)) < offset)) return -1;
    const Vec3 at = p_[v];
    p_[v] = to;
    std::vector<std::pair<int32_t, Vec3>> pushed;  // interior nodes moved, and where they were
    for (int round = 0; round < kPushRounds && !star_positive(v); ++round)
      stars_.for_each(v, [&](int32_t t) {
        if (stays(t) && quality(t) <= kPushedQuality)
          for (int k = 0; k < 4; ++k) push_away(t, k, v, pushed);
      });
    bool fits = star_positive(v);
    for (const auto& [u, from] : pushed) fits = fits && star_positive(u);
    p_[v] = at;
    if (fits) return move_to(v, to);
    for (auto it = pushed.rbegin(); it != pushed.rend(); ++it) p_[it->first] = it->second;
    return -1;
  }

 private:
  // v to x, its caps that fall under kCapQuality dropped; returns how many.
  int move_to(int32_t v, Vec3 x) {
    int caps = 0;
    stars_.for_each(v, [&](int32_t t) {
      if (!drop_[t] && capped(t, quality_with(t, v, x))) {
        drop_[t] = 1;
        ++caps;
      }
    });
    p_[v] = x;
    return caps;
  }

  // A cap of quality q goes (the rule of settle's moves).
  bool capped(int32_t t, double q) const { return is_cap(t) && q < kCapQuality; }
  // t is kept with the nodes where they are now.
  bool stays(int32_t t) const { return !drop_[t] && !capped(t, quality(t)); }
  bool star_positive(int32_t u) const {
    bool positive = true;
    stars_.for_each(u, [&](int32_t t) { positive = positive && (!stays(t) || quality(t) > 0.0); });
    return positive;
  }

  // settle_pushing's step for corner k of t (a free interior node other than v): away from the
  // opposite face by the least of a few lengths that lifts t over kPushedQuality and keeps the
  // node inside with its star positive; the node and where it was join `pushed`.
  void push_away(int32_t t, int k, int32_t v, std::vector<std::pair<int32_t, Vec3>>& pushed) {
    const int32_t u = t_[t][k];
    if (u == v || u < fixed_ || on_surface_[u]) return;
    const Vec3 away = volume_gradient(t, k);
    const double edge = stars_.mean_edge(u, p_, t_);
    const Vec3 from = p_[u];
    for (double f : {0.05, 0.1, 0.2}) {
      p_[u] = from + f * edge * away;
      if (domain_.distance(p_[u]) < 0.0 && star_positive(u) && quality(t) > kPushedQuality) {
        pushed.push_back({u, from});
        return;
      }
    }
    p_[u] = from;
  }

  double quality(int32_t t) const {
    const auto& v = t_[t];
    return settled_quality(p_[v[0]], p_[v[1]], p_[v[2]], p_[v[3]]);
  }

  // q, or 0 where the validity check would call the tetrahedron degenerate: four corners near a
  // line keep a q far above 0 (tet_validity.h), and no move may leave one for the check.
  static double settled_quality(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const double q = oriented_tet_radius_ratio(a, b, c, d);
    return degenerate_tet(a, b, c, d) ? std::min(0.0, q) : q;
  }

  // The unit direction in which corner k of t moves to grow its volume the fastest.
  Vec3 volume_gradient(int32_t t, int k) const {
    Vec3 q[4];
    for (int i = 0; i < 4; ++i) q[i] = p_[t_[t][(k + i) % 4]];
    // 6 V of (q0, q1, q2, q3) is (q1 - q0) . ((q2 - q1) x (q3 - q1)), whose gradient in q0 is
    // -(q2 - q1) x (q3 - q1); a rotation by an odd k turns the orientation over.
    Vec3 n = cross(q[2] - q[1], q[3] - q[1]);
    if (k % 2 == 0) n = -1.0 * n;
    const double length = norm(n);
    return length > 0.0 ? (1.0 / length) * n : Vec3{};
  }

  double quality_with(int32_t t, int32_t v, Vec3 x) const {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k) q[k] = t_[t][k] == v ? x : p_[t_[t][k]];
    return settled_quality(q[0], q[1], q[2], q[3]);
  }

  bool is_cap(int32_t t) const {
    for (int32_t u : t_[t])
      if (!on_surface_[u]) return false;
    return true;
  }

  // What moving v to x would do: the worst of the tetrahedra that stay (the caps it drops
  // aside).
  struct Outcome {
    double worst = -INFINITY;
    bool fits() const { return worst > 0.0; }
  };
  Outcome outcome(int32_t v, Vec3 x) const {
    Outcome o;
    o.worst = INFINITY;
    stars_.for_each(v, [&](int32_t t) {
      if (drop_[t]) return;
      const double q = quality_with(t, v, x);
      if (!capped(t, q)) o.worst = std::min(o.worst, q);
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
  int64_t fixed_;
  std::vector<char> on_surface_;
  TetStars stars_;
  std::vector<char> drop_;
};

// One round over the surface nodes off the boundary; the caps it drops leave `tets`.
SurfaceSettling settle_round(const Domain3& domain, double step, std::vector<Vec3>& points,
                             std::vector<std::array<int32_t, 4>>& tets, int64_t fixed,
                             ThreadPool* pool) {
  SurfaceSettler settler(domain, step, points, tets, fixed);
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
    for (size_t i = 0; i < group.size(); ++i) {
      const int c = caps[i] >= 0 ? caps[i] : settler.settle_pushing(group[i]);
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
