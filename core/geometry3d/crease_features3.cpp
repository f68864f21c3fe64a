#include "core/geometry3d/crease_features3.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/spaced_points3.h"

namespace meshd {
namespace {

constexpr int kNewtonSteps = 12;

class CreaseFinder {
 public:
  CreaseFinder(const Program3& program, double spacing)
      : view_(program.view()), spacing_(spacing), step_(1e-7 * spacing) {
    by_primitive_.resize(program.primitives.size(), nullptr);
    for (const Instruction3& ins : program.code)
      if (ins.primitive >= 0) by_primitive_[ins.primitive] = &ins;
  }

  double whole(Vec3 p, int* owner) const { return eval_sdf3(view_, p, owner, 2.0 * spacing_); }

  // The point of the curve where primitives i and j both read 0 nearest to `from`, if Newton
  // finds one within a spacing and the surfaces cross there at more than kCreaseAngleDeg.
  bool meet(int i, int j, Vec3 from, Vec3& out) const {
    Vec3 p = from;
    for (int k = 0; k < kNewtonSteps; ++k) {
      const double di = own(i, p), dj = own(j, p);
      const Vec3 gi = gradient(i, p, di), gj = gradient(j, p, dj);
      // The least-norm step solving gi.s = -di, gj.s = -dj.
      const double a = dot(gi, gi), b = dot(gi, gj), c = dot(gj, gj), det = a * c - b * b;
      if (!(det > 1e-12 * a * c)) return false;  // parallel: no crease
      const double li = (c * di - b * dj) / det, lj = (a * dj - b * di) / det;
      p = p - li * gi - lj * gj;
      if (!(norm(p - from) < spacing_)) return false;
    }
    const double di = own(i, p), dj = own(j, p);
    const double tol = 1e-9 * spacing_;
    if (!(std::fabs(di) <= tol && std::fabs(dj) <= tol)) return false;
    const Vec3 gi = gradient(i, p, di), gj = gradient(j, p, dj);
    const double cos_angle = dot(gi, gj) / std::sqrt(dot(gi, gi) * dot(gj, gj));
    if (std::fabs(cos_angle) > std::cos(kCreaseAngleDeg * std::numbers::pi / 180.0)) return false;
    out = p;
    return true;
  }

 private:
  double own(int i, Vec3 p) const { return sdf3_primitive(view_, *by_primitive_[i], p, INFINITY); }
  // Central differences: a primitive's distance is smooth on its own surface away from its own
  // edges, which the primitives' features already hold.
  Vec3 gradient(int i, Vec3 p, double) const {
    const double h = step_;
    return {(own(i, {p.x + h, p.y, p.z}) - own(i, {p.x - h, p.y, p.z})) / (2 * h),
            (own(i, {p.x, p.y + h, p.z}) - own(i, {p.x, p.y - h, p.z})) / (2 * h),
            (own(i, {p.x, p.y, p.z + h}) - own(i, {p.x, p.y, p.z - h})) / (2 * h)};
  }

  Program3View view_;
  double spacing_;
  double step_;
  std::vector<const Instruction3*> by_primitive_;
};

}  // namespace

std::vector<Vec3> crease_features3(const Program3& program, const Box3& bounds, double spacing,
                                   const std::vector<Vec3>& existing) {
  std::vector<Vec3> out;
  if (program.primitives.size() < 2 || !(spacing > 0.0)) return out;
  const Vec3 extent = bounds.max - bounds.min;
  double cell = spacing;
  const auto samples = [&](double c) {
    return (std::floor(extent.x / c) + 2) * (std::floor(extent.y / c) + 2) *
           (std::floor(extent.z / c) + 2);
  };
  while (samples(cell) > kMaxCreaseGridSamples) cell *= 1.25;
  const auto nx = static_cast<int64_t>(std::floor(extent.x / cell)) + 2;
  const auto ny = static_cast<int64_t>(std::floor(extent.y / cell)) + 2;
  const auto nz = static_cast<int64_t>(std::floor(extent.z / cell)) + 2;
  const Vec3 origin = bounds.min - Vec3{0.5 * cell, 0.5 * cell, 0.5 * cell};
  const auto at = [&](int64_t x, int64_t y, int64_t z) {
    return origin + Vec3{x * cell, y * cell, z * cell};
  };

  const CreaseFinder finder(program, spacing);
  std::vector<int> owner(static_cast<size_t>(nx * ny * nz), -1);  // -1: far from the boundary
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y)
      for (int64_t x = 0; x < nx; ++x) {
        int who = -1;
        const double d = finder.whole(at(x, y, z), &who);
        if (std::fabs(d) < cell) owner[(z * ny + y) * nx + x] = who;
      }

  SpacedPoints3 kept(kCreaseGapFraction * spacing);
  for (Vec3 p : existing) kept.add(p);
  const double on_boundary = 1e-9 * spacing;
  const auto consider = [&](int a, int b, Vec3 pa, Vec3 pb) {
    if (a < 0 || b < 0 || a == b) return;
    Vec3 p;
    if (!finder.meet(std::min(a, b), std::max(a, b), 0.5 * (pa + pb), p)) return;
    int who = -1;
    const double size = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    if (!(std::fabs(finder.whole(p, &who)) <= on_boundary + 1e-12 * size)) return;
    if (kept.near(p)) return;
    kept.add(p);
    out.push_back(p);
  };
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y)
      for (int64_t x = 0; x < nx; ++x) {
        const int a = owner[(z * ny + y) * nx + x];
        if (a < 0) continue;
        const Vec3 pa = at(x, y, z);
        if (x + 1 < nx) consider(a, owner[(z * ny + y) * nx + x + 1], pa, at(x + 1, y, z));
        if (y + 1 < ny) consider(a, owner[(z * ny + y + 1) * nx + x], pa, at(x, y + 1, z));
        if (z + 1 < nz) consider(a, owner[((z + 1) * ny + y) * nx + x], pa, at(x, y, z + 1));
      }
  return out;
}

}  // namespace meshd
