// The repair of a kept tetrahedralization by flips (flip_repair3.h) against CGAL: after small
// moves the repaired tetrahedra are positive, conforming and locally Delaunay under exact
// predicates, and (random points, whose Delaunay tetrahedralization is unique) CGAL's; on a
// lattice's cospherical points they are valid; what flips cannot mend (tetrahedra left turned
// over) is reported, tetrahedron for tetrahedron.
#include "core/delaunay/flip_repair3.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "core/delaunay/delaunay3d.h"
#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/filtered_predicates3.cuh"
#include "tests/core/random_points3.h"

namespace meshd {
namespace {

using Tets = std::vector<std::array<int32_t, 4>>;

// The repair of CGAL's tetrahedra of `before` for the points `after`.
struct Repaired {
  RepairOutcome3 outcome;
  Tets tets;
};

Repaired repair(const std::vector<Vec3>& before, const std::vector<Vec3>& after) {
  FlipRepair3 kept;
  EXPECT_TRUE(kept.keep(delaunay_tetrahedralize(before, 4), static_cast<int64_t>(before.size())));
  Repaired r;
  r.outcome = kept.repair(after);
  if (r.outcome.ended) r.tets = kept.tets();
  return r;
}

// Each tetrahedron starting at its lowest vertex by an even permutation, then sorted: the
// order delaunay3d.h returns.
Tets canonical(Tets tets) {
  for (auto& t : tets) {
    const auto lowest = std::min_element(t.begin(), t.end()) - t.begin();
    if (lowest == 1) t = {t[1], t[0], t[3], t[2]};
    if (lowest == 2) t = {t[2], t[3], t[0], t[1]};
    if (lowest == 3) t = {t[3], t[2], t[1], t[0]};
    while (t[1] > t[2] || t[1] > t[3]) t = {t[0], t[2], t[3], t[1]};
  }
  std::sort(tets.begin(), tets.end());
  return tets;
}

double volume(const std::vector<Vec3>& p, const std::array<int32_t, 4>& t) {
  const Vec3 a = p[t[0]];
  return dot(p[t[1]] - a, cross(p[t[2]] - a, p[t[3]] - a)) / 6.0;
}

// What the repair reported: every tetrahedron positive for certain but the `inverted` ones,
// every face in at most two tetrahedra but the `overfull` third ones; (`delaunay`) no face whose
// opposite apex lies strictly inside the other's sphere.
void expect_as_reported(const std::vector<Vec3>& p, const Tets& tets, const RepairOutcome3& o,
                        bool delaunay) {
  std::map<std::array<int32_t, 3>, std::vector<std::pair<size_t, int>>> sides;
  int64_t not_positive = 0, overfull = 0;
  for (size_t i = 0; i < tets.size(); ++i) {
    const auto& t = tets[i];
    not_positive += orientation3_filtered(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) != 1;
    if (o.inverted == 0) {
      ASSERT_EQ(orientation3_sign(p[t[0]], p[t[1]], p[t[2]], p[t[3]]), 1) << i;
    }
    for (int f = 0; f < 4; ++f) {
      std::array<int32_t, 3> face{t[(f + 1) % 4], t[(f + 2) % 4], t[(f + 3) % 4]};
      std::sort(face.begin(), face.end());
      sides[face].push_back({i, f});
    }
  }
  EXPECT_EQ(not_positive, o.inverted);
  int violations = 0;
  for (const auto& [face, users] : sides) {
    overfull += std::max<int64_t>(0, static_cast<int64_t>(users.size()) - 2);
    if (!delaunay || users.size() != 2) continue;
    const auto& t = tets[users[0].first];
    const Vec3 apex = p[tets[users[1].first][users[1].second]];
    violations += in_sphere_sign(p[t[0]], p[t[1]], p[t[2]], p[t[3]], apex) > 0;
  }
  EXPECT_EQ(overfull, o.overfull);
  EXPECT_EQ(violations, 0);
}

double total_volume(const std::vector<Vec3>& p, const Tets& tets) {
  double v = 0.0;
  for (const auto& t : tets) v += volume(p, t);
  return v;
}

double spacing_of(size_t n) { return 2.0 / std::cbrt(static_cast<double>(n)); }

// A thousandth of the spacing: hundreds of faces to flip, and (random points have slivers
// flatter than any bound) none of them turned over yet.
TEST(FlipRepair3, GivesCgalsTetrahedraOfSlightlyMovedRandomPoints) {
  for (const size_t n : {2000u, 20000u}) {
    const std::vector<Vec3> before = testing::random_points3(n, 5);
    const std::vector<Vec3> after = testing::moved_inner3(before, 0.001 * spacing_of(n), 6);
    const Repaired r = repair(before, after);
    ASSERT_TRUE(r.outcome.clean())
        << "n " << n << ": ended " << r.outcome.ended << ", overfull " << r.outcome.overfull
        << ", inverted " << r.outcome.inverted << ", stuck " << r.outcome.stuck;
    EXPECT_GT(r.outcome.flips, static_cast<int64_t>(n / 200)) << n;
    expect_as_reported(after, r.tets, r.outcome, true);
    EXPECT_EQ(canonical(r.tets), delaunay_tetrahedralize(after, 4)) << n;
  }
}

// A fifth of the spacing turns slivers of random points over, which the flips leave, and
// flips beside them can make a face twice: the repair ends, and reports them all.
TEST(FlipRepair3, ReportsWhatFlipsCannotMend) {
  const size_t n = 20000;
  const std::vector<Vec3> before = testing::random_points3(n, 5);
  const std::vector<Vec3> after = testing::moved_inner3(before, 0.2 * spacing_of(n), 6);
  const Repaired r = repair(before, after);
  ASSERT_TRUE(r.outcome.ended);
  EXPECT_GT(r.outcome.flips, static_cast<int64_t>(n / 10));
  EXPECT_GT(r.outcome.inverted, 0);
  expect_as_reported(after, r.tets, r.outcome, false);
}

TEST(FlipRepair3, KeepsALatticesCosphericalPointsValid) {
  std::vector<Vec3> before;
  for (int i = 0; i <= 12; ++i)
    for (int j = 0; j <= 12; ++j)
      for (int k = 0; k <= 12; ++k) before.push_back({i / 6.0 - 1.0, j / 6.0 - 1.0, k / 6.0 - 1.0});
  // Every other inner point moves a little; the rest keep their cospherical cubes.
  std::vector<Vec3> after = before;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.002, 0.002);
  for (size_t i = 0; i < after.size(); i += 2) {
    const Vec3 q = after[i];
    if (std::fabs(q.x) < 0.9 && std::fabs(q.y) < 0.9 && std::fabs(q.z) < 0.9)
      after[i] = q + Vec3{u(rng), u(rng), u(rng)};
  }
  const Repaired r = repair(before, after);
  ASSERT_TRUE(r.outcome.ended);
  EXPECT_GT(r.outcome.flips, 0);
  ASSERT_TRUE(r.outcome.clean());
  expect_as_reported(after, r.tets, r.outcome, false);
  { EXPECT_NEAR(total_volume(after, r.tets), 8.0, 1e-9); }
}

// A point thrown across the cube turns its tetrahedra over; flips cannot take a point's star
// elsewhere, and the repair says so.
TEST(FlipRepair3, ReportsAPointThrownAcross) {
  const std::vector<Vec3> before = testing::random_points3(3000, 8);
  std::vector<Vec3> after = before;
  for (Vec3& q : after)
    if (std::fabs(q.x) < 0.5 && std::fabs(q.y) < 0.5 && std::fabs(q.z) < 0.5 && norm(q) > 0.3) {
      q = Vec3{-q.x, -q.y, -q.z};
      break;
    }
  const Repaired r = repair(before, after);
  ASSERT_TRUE(r.outcome.ended);
  EXPECT_GT(r.outcome.inverted, 0);
  expect_as_reported(after, r.tets, r.outcome, false);
}

}  // namespace
}  // namespace meshd
