// The one signed-distance evaluator, compiled by g++ for the CPU engine and by nvcc for the GPU
// engine. Distances are exact for every analytic primitive, and as exact as the data for a
// sampled grid (grid_sdf.cuh); CSG combinations use min / max as DistMesh does (exact outside a
// union, a bound elsewhere).
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/geometry/grid_sdf.cuh"
#include "core/geometry/polygon_sdf.cuh"
#include "core/geometry/program.h"

namespace meshd {

// Plain sqrt rather than hypot: libm's hypot guards against overflow that lengths in a mesh
// never reach, and costs several times more on the hot path.
MESHD_HD inline double length2d(double x, double y) { return sqrt(x * x + y * y); }
MESHD_HD inline double max2(double a, double b) { return a > b ? a : b; }
MESHD_HD inline double min2(double a, double b) { return a < b ? a : b; }

MESHD_HD inline double sdf_circle(const double* q, Vec2 p) {
  return length2d(p.x - q[0], p.y - q[1]) - q[2];
}

// Exact box distance, including the rounded distance field outside its corners.
MESHD_HD inline double sdf_box(const double* q, Vec2 p) {
  const double dx = p.x - q[0], dy = p.y - q[1];
  const double lx = fabs(q[4] * dx + q[5] * dy) - q[2];
  const double ly = fabs(-q[5] * dx + q[4] * dy) - q[3];
  const double ox = max2(lx, 0.0), oy = max2(ly, 0.0);
  return length2d(ox, oy) + min2(max2(lx, ly), 0.0);
}

// A distance grid (grid_sdf.cuh): the samples' interpolant cut by the grid's box, both in the
// grid's frame, the box's distance as sdf_box's for an unrotated box.
MESHD_HD inline double sdf_grid(const double* params, const float* samples, uint32_t offset,
                                Vec2 p) {
  const double* q = params + offset;
  const RegularGrid g = grid_at(params, samples, offset);
  const Vec2 l = grid_local(q, p);
  const Box b = g.box();
  const double box[6] = {0.5 * (b.min.x + b.max.x),
                         0.5 * (b.min.y + b.max.y),
                         0.5 * (b.max.x - b.min.x),
                         0.5 * (b.max.y - b.min.y),
                         1.0,
                         0.0};
  return q[kGridParams + 4] * max2(bilinear(g, l), sdf_box(box, l));
}

MESHD_HD inline double sdf_half_plane(const double* q, Vec2 p) {
  return q[0] * p.x + q[1] * p.y - q[2];
}

// Distance from (y0, y1), y >= 0, to the ellipse with semi axes e0 >= e1 > 0 (Eberly's
// formulation, in the variable t = s + 1). The closest point is x0 = r0 y0 / (t + r0 - 1),
// x1 = y1 / t, with t the root of the convex, decreasing G below. Solving for t itself rather
// than for s = t - 1 keeps full relative precision when the point lies near the major axis,
// where t is as small as y1. Newton's method from the left end of the bracket converges
// monotonically; bisection takes over whenever a step would leave the bracket.
MESHD_HD inline double ellipse_distance_quadrant(double e0, double e1, double y0, double y1) {
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) return 0.0;
      const double r0 = (e0 / e1) * (e0 / e1);
      const double c = r0 - 1.0;
      const double n0 = r0 * z0;
      // G(lo) >= 0: one of its two terms is 1 there. Starting at the larger bound keeps Newton
      // within a small factor of the root (from t = z1 alone a circle needs ~100 steps).
      double lo = max2(z1, n0 - c);
      double hi = g < 0.0 ? 1.0 : length2d(n0, z1);  // G(hi) <= 0
      double t = lo;
      for (int it = 0; it < 100; ++it) {
        const double a = n0 / (t + c), b = z1 / t;
        const double G = a * a + b * b - 1.0;
        if (G == 0.0) break;
        if (G > 0.0)
          lo = t;
        else
          hi = t;
        const double dG = -2.0 * (a * a / (t + c) + b * b / t);
        double next = t - G / dG;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (fabs(next - t) <= 1e-15 * t) {
          t = next;
          break;
        }
        t = next;
      }
      const double x0 = r0 * y0 / (t + c), x1 = y1 / t;
      return length2d(x0 - y0, x1 - y1);
    }
    return fabs(y1 - e1);
  }
  const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    const double x0 = e0 * xde0, x1 = e1 * sqrt(max2(1.0 - xde0 * xde0, 0.0));
    return length2d(x0 - y0, x1);
  }
  return fabs(y0 - e0);
}

MESHD_HD inline double sdf_ellipse(const double* q, Vec2 p) {
  const double dx = p.x - q[0], dy = p.y - q[1];
  const double lx = q[4] * dx + q[5] * dy, ly = -q[5] * dx + q[4] * dy;
  const double a = q[2], b = q[3];
  const bool inside = (lx / a) * (lx / a) + (ly / b) * (ly / b) < 1.0;
  const double d = a >= b ? ellipse_distance_quadrant(a, b, fabs(lx), fabs(ly))
                          : ellipse_distance_quadrant(b, a, fabs(ly), fabs(lx));
  return inside ? -d : d;
}

MESHD_HD inline double sdf_primitive(ProgramView prog, const Instruction& ins, Vec2 p) {
  const double* q = prog.params + ins.operand;
  switch (ins.op) {
    case Op::kCircle:
      return sdf_circle(q, p);
    case Op::kBox:
      return sdf_box(q, p);
    case Op::kEllipse:
      return sdf_ellipse(q, p);
    case Op::kHalfPlane:
      return sdf_half_plane(q, p);
    case Op::kPolygon:
      return ins.bvh == kNoBvh ? sdf_polygon(q, p) : sdf_polygon_indexed(q, prog.nodes, ins.bvh, p);
    case Op::kGrid:
      return sdf_grid(prog.params, prog.samples, ins.operand, p);
    default:
      return NAN;
  }
}

// How many kUnionIndexed levels the evaluator follows through its index; deeper ones run their
// plain fold. A template parameter rather than recursion, which device code would pay for. On
// the device one level, because every level inlines another evaluator into each kernel (on an
// H100, a second level took the step kernels from 86 to 110 registers and slowed G5 at 1M by
// about a quarter; with one level, G1-G5 and the examples ran as fast as with no index at all).
// The host has no such cost, and its second level serves a union of polygons with many holes
// each (an imported coastline: the holes of each land polygon are a nested indexed union).
#ifdef __CUDA_ARCH__
constexpr int kIndexedUnionLevels = 1;
#else
constexpr int kIndexedUnionLevels = 2;
#endif

template <int kLevels, int kStack = kMaxProgramStack>
MESHD_HD double eval_program(ProgramView prog, uint32_t begin, uint32_t end, Vec2 p, int* owner);

// The union that the kUnionIndexed instruction `ins` opens: the smallest operand value, from
// the operands whose boxes could hold it. An operand's value is at least the distance to its
// box from outside it (box_bounds in bounds.h), so a box farther than the best value so far is
// skipped; a box containing p never is, its operand may be negative there. Ties go to the
// earlier operand, as in the fold.
template <int kLevels>
MESHD_HD double eval_union_indexed(ProgramView prog, const Instruction& ins, Vec2 p, int* owner) {
  double best = INFINITY;
  uint32_t best_first = 0xffffffffu;
  int best_owner = -1;
  uint32_t stack[kMaxBvhDepth + 2];
  int top = 0;
  stack[0] = ins.bvh;
  while (top >= 0) {
    const BvhNode& node = prog.nodes[stack[top--]];
    const double d2 = box_distance2(node.box, p);
    if (d2 > 0.0 && (best <= 0.0 || d2 > best * best)) continue;
    if (node.leaf) {
      int who = -1;
      const double value =
          eval_program<kLevels, kMaxIndexedOperandStack>(prog, node.first, node.last, p, &who);
      if (value < best || (value == best && node.first < best_first)) {
        best = value;
        best_first = node.first;
        best_owner = who;
      }
      continue;
    }
    const double dl = box_distance2(prog.nodes[node.first].box, p);
    const double dr = box_distance2(prog.nodes[node.last].box, p);
    stack[++top] = dl <= dr ? node.last : node.first;
    stack[++top] = dl <= dr ? node.first : node.last;
  }
  *owner = best_owner;
  return best;
}

// g++ cannot see that a compiled program always pushes before it pops, and where this inlines
// deep enough it warns that the stack may be read uninitialised. Initialising the stack would
// cost every evaluation a store on the GPU's hot path, so the warning is silenced here alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
// Signed distance of the program's instructions [begin, end) at p, following kLevels levels of
// indexed unions. When `owner` is not null it receives the index of the primitive whose
// distance the result is (the boundary it is nearest to), which tags boundary edges.
template <int kLevels, int kStack>
MESHD_HD double eval_program(ProgramView prog, uint32_t begin, uint32_t end, Vec2 p, int* owner) {
  double value[kStack];
  int who[kStack];
  int top = -1;
  for (uint32_t i = begin; i < end; ++i) {
    const Instruction ins = prog.code[i];
    switch (ins.op) {
      case Op::kMin:
        --top;
        if (value[top + 1] < value[top]) {
          value[top] = value[top + 1];
          who[top] = who[top + 1];
        }
        break;
      case Op::kMax:
        --top;
        if (value[top + 1] > value[top]) {
          value[top] = value[top + 1];
          who[top] = who[top + 1];
        }
        break;
      case Op::kNegate:
        value[top] = -value[top];
        break;
      case Op::kUnionIndexed:
        if constexpr (kLevels > 0) {
          if (ins.bvh == kNoBvh) break;
          ++top;
          value[top] = eval_union_indexed<kLevels - 1>(prog, ins, p, &who[top]);
          i = ins.operand - 1;
        }
        break;  // with no level or no tree, the fold that follows computes the same union
      default:
        ++top;
        value[top] = sdf_primitive(prog, ins, p);
        who[top] = ins.primitive;
        break;
    }
  }
  if (owner != nullptr) *owner = who[0];
  return value[0];
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

MESHD_HD inline double eval_sdf_range(ProgramView prog, uint32_t begin, uint32_t end, Vec2 p,
                                      int* owner = nullptr) {
  return eval_program<kIndexedUnionLevels>(prog, begin, end, p, owner);
}

MESHD_HD inline double eval_sdf(ProgramView prog, Vec2 p) {
  return eval_sdf_range(prog, 0, prog.size, p);
}

// The same through two levels of index where `nested` (nests_indexed_unions in compile.h): on
// the device a coastline's lakes would otherwise be folded in full at every point (the whole
// Archipelago Sea: a land polygon with 166 lakes), while the programs that need one level keep
// the lighter evaluator. The same value either way; the host always follows two levels.
MESHD_HD inline double eval_sdf(ProgramView prog, Vec2 p, bool nested) {
  return nested ? eval_program<2>(prog, 0, prog.size, p, nullptr) : eval_sdf(prog, p);
}

}  // namespace meshd
