#include "core/geometry/bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/geometry/regular_grid.h"

namespace meshd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const Box kWholePlane{{-kInf, -kInf}, {kInf, kInf}};

Box primitive_box(Op op, const double* q) {
  switch (op) {
    case Op::kCircle:
      return {{q[0] - q[2], q[1] - q[2]}, {q[0] + q[2], q[1] + q[2]}};
    case Op::kBox:
    case Op::kEllipse: {
      // Extent of a rotated box (|c| hx + |s| hy) or ellipse (sqrt((c a)^2 + (s b)^2)).
      const double c = q[4], s = q[5];
      const double ex = op == Op::kBox ? std::fabs(c) * q[2] + std::fabs(s) * q[3]
                                       : std::hypot(c * q[2], s * q[3]);
      const double ey = op == Op::kBox ? std::fabs(s) * q[2] + std::fabs(c) * q[3]
                                       : std::hypot(s * q[2], c * q[3]);
      return {{q[0] - ex, q[1] - ey}, {q[0] + ex, q[1] + ey}};
    }
    case Op::kPolygon: {
      Box b{{kInf, kInf}, {-kInf, -kInf}};
      const int n = static_cast<int>(q[0]);
      for (int i = 0; i < n; ++i) {
        b.min = {std::min(b.min.x, q[1 + 2 * i]), std::min(b.min.y, q[2 + 2 * i])};
        b.max = {std::max(b.max.x, q[1 + 2 * i]), std::max(b.max.y, q[2 + 2 * i])};
      }
      return b;
    }
    case Op::kGrid: {
      // The grid's box mapped from its own frame to the world's (program.h): a rotated box.
      const double* t = q + kGridParams;
      const double hx = 0.5 * t[4] * (q[4] - 1) * q[2], hy = 0.5 * t[4] * (q[5] - 1) * q[3];
      const double cx = q[0] + 0.5 * (q[4] - 1) * q[2], cy = q[1] + 0.5 * (q[5] - 1) * q[3];
      const double c = t[2], s = t[3];
      const Vec2 center{t[0] + t[4] * (c * cx - s * cy), t[1] + t[4] * (s * cx + c * cy)};
      const double ex = std::fabs(c) * hx + std::fabs(s) * hy;
      const double ey = std::fabs(s) * hx + std::fabs(c) * hy;
      return {{center.x - ex, center.y - ey}, {center.x + ex, center.y + ey}};
    }
    default:  // a half-plane is unbounded
      return kWholePlane;
  }
}

double area(const Box& b) { return (b.max.x - b.min.x) * (b.max.y - b.min.y); }

// The walk both boxes share; `overlap` says whether a kMax takes the overlap of its operands'
// boxes (a box holding the domain) or the smaller of them (a distance bound).
Box walk_bounds(const Program& program, uint32_t begin, uint32_t end, bool overlap) {
  std::vector<Box> stack;
  for (uint32_t i = begin; i < end; ++i) {
    const Instruction& ins = program.code[i];
    if (ins.op == Op::kUnionIndexed) continue;  // its fold follows
    if (ins.op == Op::kNegate) {
      stack.back() = kWholePlane;
    } else if (ins.op == Op::kMin || ins.op == Op::kMax) {
      const Box b = stack.back();
      stack.pop_back();
      Box& a = stack.back();
      if (ins.op == Op::kMin) {
        a = {{std::min(a.min.x, b.min.x), std::min(a.min.y, b.min.y)},
             {std::max(a.max.x, b.max.x), std::max(a.max.y, b.max.y)}};
      } else if (overlap) {
        a = {{std::max(a.min.x, b.min.x), std::max(a.min.y, b.min.y)},
             {std::min(a.max.x, b.max.x), std::min(a.max.y, b.max.y)}};
      } else if (!(area(a) <= area(b))) {
        a = b;
      }
    } else {
      stack.push_back(primitive_box(ins.op, program.params.data() + ins.operand));
    }
  }
  return stack.empty() ? Box{{kInf, kInf}, {-kInf, -kInf}} : stack.back();
}

}  // namespace

Box program_bounds(const Program& program, uint32_t begin, uint32_t end) {
  return walk_bounds(program, begin, end, true);
}

Box distance_bound_box(const Program& program, uint32_t begin, uint32_t end) {
  return walk_bounds(program, begin, end, false);
}

}  // namespace meshd
