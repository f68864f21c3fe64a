#include "core/delaunay/parallel_insertion.h"

#include <algorithm>
#include <numeric>

#include "core/common/error.h"
#include "core/delaunay/complete_triangulation.h"
#include "core/delaunay/lawson_repair.h"
#include "core/delaunay/parallel_insertion.cuh"

namespace meshd {

std::vector<int32_t> distinct_points(const std::vector<Vec2>& points) {
  std::vector<int32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  const auto less = [&](int32_t i, int32_t j) {
    const Vec2 a = points[i], b = points[j];
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && i < j)));
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int32_t> kept;
  for (size_t k = 0; k < order.size(); ++k) {
    const Vec2 a = points[order[k]];
    if (k > 0 && a.x == points[order[k - 1]].x && a.y == points[order[k - 1]].y) continue;
    kept.push_back(order[k]);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

namespace {

// The insertion's arrays on the host, and its steps run one element after the other: each
// step's loops read only what the step before wrote, as the device's kernels do.
class HostInsertion {
 public:
  explicit HostInsertion(const std::vector<Vec2>& points)
      : n_(static_cast<int32_t>(points.size())) {
    p_ = points;
    Vec2 lo = points.empty() ? Vec2{} : points[0], hi = lo;
    for (const Vec2& q : points) {
      lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
      hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
    }
    Vec2 corners[3];
    enclosing_triangle(lo, hi, corners);
    p_.insert(p_.end(), corners, corners + 3);
    const size_t room = 2 * static_cast<size_t>(n_) + 1;
    tris_.resize(room);
    nbrs_.resize(room);
    vote_.resize(room);
    family_.assign(2 * room, -1);
    stamp_.assign(room, -1);
    loc_.assign(n_, 0);
    edge_.assign(n_, -1);
    tris_[0] = Tri{{n_, n_ + 1, n_ + 2}};
    nbrs_[0] = Tri{{-1, -1, -1}};
    s_ = InsertionState{p_.data(),     n_,           tris_.data(), nbrs_.data(),
                        loc_.data(),   edge_.data(), vote_.data(), family_.data(),
                        stamp_.data(), &flips_,      &lost_};
  }

  // Until no point is left to win a triangle, with the device's steps and step numbers.
  void run(InsertionStats& stats) {
    int32_t since = -1;  // the first step whose changes the flips have not settled
    for (;;) {
      ++step_;
      if (since < 0) since = step_;
      std::fill(vote_.begin(), vote_.begin() + m_, kNoVote);
      for (int32_t i = 0; i < n_; ++i) vote_for_point(s_, i);
      std::vector<int32_t> winners;
      for (int32_t i = 0; i < n_; ++i)
        if (point_wins(s_, i)) winners.push_back(i);
      if (winners.empty()) break;
      for (size_t w = 0; w < winners.size(); ++w)
        insert_point(s_, winners[w], m_ + 2 * static_cast<int32_t>(w), step_);
      m_ += 2 * static_cast<int32_t>(winners.size());
      after_step();
      ++stats.insertion_steps;
      since = flip(since, true, stats);
    }
    if (since >= 0) flip(since, false, stats);
    if (lost_ > 0) throw Error(ErrorCode::kInternal, "", "point insertion lost a point");
  }

  // Flip steps over what changed since step `since`, until none flips or, when `may_wait`, the
  // cascade's tail (flips_may_wait). Returns the `since` of the next insertion: -1 when settled.
  int32_t flip(int32_t since, bool may_wait, InsertionStats& stats) {
    int64_t first = -1;
    for (;;) {
      ++step_;
      std::fill(vote_.begin(), vote_.begin() + m_, kNoVote);
      for (int32_t t = 0; t < m_; ++t) vote_for_flips(s_, t, since, step_);
      flips_ = 0;
      for (int32_t t = 0; t < m_; ++t) flip_won_edge(s_, t, step_);
      after_step();
      ++stats.flip_steps;
      stats.flips += flips_;
      if (flips_ == 0) return -1;
      if (first < 0) {
        first = flips_;
      } else if (may_wait && flips_may_wait(first, flips_)) {
        return since;
      }
    }
  }

  // The triangles of the points alone, without the enclosing triangle's corners.
  Triangulation real_triangles() const {
    Triangulation t;
    t.triangles.reserve(m_);
    t.neighbors.reserve(m_);
    for (int32_t x = 0; x < m_; ++x) {
      const Tri& v = tris_[x];
      t.triangles.push_back({v.v[0], v.v[1], v.v[2]});
      t.neighbors.push_back({nbrs_[x].v[0], nbrs_[x].v[1], nbrs_[x].v[2]});
    }
    std::vector<char> drop(m_);
    for (int32_t x = 0; x < m_; ++x)
      drop[x] = *std::max_element(t.triangles[x].begin(), t.triangles[x].end()) >= n_;
    drop_triangles(t, drop);
    return t;
  }

 private:
  void after_step() {
    for (int32_t x = 0; x < m_; ++x)
      if (stamp_[x] == step_) relink_triangle(s_, x, step_);
    for (int32_t i = 0; i < n_; ++i) relocate_point(s_, i, step_);
  }

  int32_t n_;
  int32_t m_ = 1;
  int32_t step_ = 0;
  int32_t flips_ = 0, lost_ = 0;
  std::vector<Vec2> p_;
  std::vector<Tri> tris_, nbrs_;
  std::vector<unsigned long long> vote_;
  std::vector<int32_t> family_, stamp_, loc_;
  std::vector<int8_t> edge_;
  InsertionState s_{};
};

}  // namespace

Triangulation insertion_triangulate(const std::vector<Vec2>& points, InsertionStats* stats) {
  InsertionStats local;
  InsertionStats& st = stats ? *stats : local;
  const std::vector<int32_t> kept = distinct_points(points);
  st.duplicates = static_cast<int64_t>(points.size() - kept.size());
  std::vector<Vec2> distinct(kept.size());
  for (size_t k = 0; k < kept.size(); ++k) distinct[k] = points[kept[k]];

  HostInsertion insertion(distinct);
  insertion.run(st);
  Triangulation t = complete_triangulation(distinct, insertion.real_triangles(), 0);
  if (t.triangles.empty() && distinct.size() >= 3) {
    st.fell_back = true;
    t = delaunay_triangulate(distinct);
  } else {
    const RepairResult repaired = lawson_repair(distinct, std::vector<char>(t.triangles.size(), 1),
                                                std::vector<char>(distinct.size(), 0), t);
    if (!repaired.ok) throw Error(ErrorCode::kInternal, "", "point insertion left a fold");
  }
  for (auto& tri : t.triangles)
    for (int32_t& v : tri) v = kept[v];
  return t;
}

}  // namespace meshd
