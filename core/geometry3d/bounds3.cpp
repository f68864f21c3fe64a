#include "core/geometry3d/bounds3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/common/error.h"

namespace meshd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const Box3 kWholeSpace{{-kInf, -kInf, -kInf}, {kInf, kInf, kInf}};

Vec3 load(const double* q) { return {q[0], q[1], q[2]}; }

Box3 around(Vec3 c, Vec3 e) { return {c - e, c + e}; }

Box3 hull(const Box3& a, const Box3& b) {
  return {{std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y), std::min(a.min.z, b.min.z)},
          {std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y), std::max(a.max.z, b.max.z)}};
}

Box3 overlap(const Box3& a, const Box3& b) {
  return {{std::max(a.min.x, b.min.x), std::max(a.min.y, b.min.y), std::max(a.min.z, b.min.z)},
          {std::min(a.max.x, b.max.x), std::min(a.max.y, b.max.y), std::min(a.max.z, b.max.z)}};
}

// Half the extent, along each coordinate, of a disk of radius r perpendicular to the unit vector
// a: r sqrt(1 - a_i^2), written as r |a_j, a_k| so that no digit cancels where a_i is near 1.
Vec3 disk_extent(Vec3 a, double r) {
  return {r * std::sqrt(a.y * a.y + a.z * a.z), r * std::sqrt(a.x * a.x + a.z * a.z),
          r * std::sqrt(a.x * a.x + a.y * a.y)};
}

Vec3 abs3(Vec3 v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }

Box3 primitive_box(Op3 op, const double* q) {
  switch (op) {
    case Op3::kSphere:
      return around(load(q), {q[3], q[3], q[3]});
    case Op3::kCuboid:
      return around(load(q), q[12] * abs3(load(q + 3)) + q[13] * abs3(load(q + 6)) +
                                 q[14] * abs3(load(q + 9)));
    case Op3::kCylinder: {
      const Vec3 a = load(q + 3);
      return around(load(q), q[7] * abs3(a) + disk_extent(a, q[6]));
    }
    case Op3::kFrustum: {
      // The hull of its two end disks.
      const Vec3 base = load(q), a = load(q + 3);
      return hull(around(base, disk_extent(a, q[6])),
                  around(base + q[8] * a, disk_extent(a, q[7])));
    }
    case Op3::kTorus: {
      // Its centre circle of radius R, grown by the ball of radius r.
      const Vec3 e = disk_extent(load(q + 3), q[6]);
      return around(load(q), e + Vec3{q[7], q[7], q[7]});
    }
    case Op3::kExtrusion: {
      // The profile's box times [0, h], mapped by the frame.
      const double sc = q[12];
      const Vec3 u = load(q + 3), v = load(q + 6), w = load(q + 9);
      const double mx = 0.5 * (q[14] + q[16]), my = 0.5 * (q[15] + q[17]), mz = 0.5 * q[13];
      const double hx = 0.5 * (q[16] - q[14]), hy = 0.5 * (q[17] - q[15]);
      return around(load(q) + sc * (mx * u + my * v + mz * w),
                    sc * (hx * abs3(u) + hy * abs3(v) + mz * abs3(w)));
    }
    case Op3::kRevolution: {
      // A cylinder of the profile's largest x between its lowest and highest y.
      const double sc = q[6];
      const Vec3 a = load(q + 3);
      return around(load(q) + (sc * 0.5 * (q[8] + q[9])) * a,
                    (sc * 0.5 * (q[9] - q[8])) * abs3(a) + disk_extent(a, sc * q[7]));
    }
    case Op3::kPolyhedron:
      return {load(q), load(q + 3)};
    case Op3::kHalfSpace: {
      // Bounded on one side where its normal is a coordinate axis, unbounded otherwise.
      Box3 b = kWholeSpace;
      double* lo[3] = {&b.min.x, &b.min.y, &b.min.z};
      double* hi[3] = {&b.max.x, &b.max.y, &b.max.z};
      for (int k = 0; k < 3; ++k) {
        const double nk = q[k], rest = std::fabs(q[(k + 1) % 3]) + std::fabs(q[(k + 2) % 3]);
        if (rest != 0.0) continue;
        if (nk > 0.0) *hi[k] = q[3] / nk;
        if (nk < 0.0) *lo[k] = q[3] / nk;
      }
      return b;
    }
    default:
      return kWholeSpace;
  }
}

// A box on the walk's stack, and a half-space that leaves it unbounded (-1: none, or none to
// blame, as for a negated operand).
struct Entry {
  Box3 box;
  int32_t unbounded_by = -1;
};

Entry walk(const Program3& program) {
  std::vector<Entry> stack;
  for (const Instruction3& ins : program.code) {
    if (ins.op == Op3::kNegate) {
      stack.back() = {kWholeSpace, -1};
    } else if (ins.op == Op3::kMin || ins.op == Op3::kMax) {
      const Entry b = stack.back();
      stack.pop_back();
      Entry& a = stack.back();
      const bool a_unbounded = !is_bounded(a.box);
      a.box = ins.op == Op3::kMin ? hull(a.box, b.box) : overlap(a.box, b.box);
      if (is_bounded(a.box))
        a.unbounded_by = -1;
      else if (!a_unbounded)
        a.unbounded_by = b.unbounded_by;
    } else {
      const Box3 box = primitive_box(ins.op, program.params.data() + ins.operand);
      stack.push_back({box, is_bounded(box) ? -1 : ins.primitive});
    }
  }
  if (stack.empty()) return {{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}}, -1};
  return stack.back();
}

}  // namespace

Box3 program_bounds3(const Program3& program) { return walk(program).box; }

Box3 domain_bounds3(const Program3& program) {
  const Entry e = walk(program);
  if (is_empty(e.box)) {
    throw_invalid(program.root_path,
                  "the domain is empty (its intersection, or its only shape's box, is empty)");
  }
  if (!is_bounded(e.box)) {
    const bool known = e.unbounded_by >= 0;
    throw_invalid(known ? program.primitives[e.unbounded_by].path : program.root_path,
                  std::string("the domain is unbounded: ") +
                      (known ? "this half-space" : "a half-space") +
                      " must be cut off by an intersection with a bounded shape");
  }
  return e.box;
}

}  // namespace meshd
