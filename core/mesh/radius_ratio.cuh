// The radius ratio q = 2 r_in / R_circ of a triangle (simpqual.m): 1 for an equilateral
// triangle, 0 for a degenerate one. Shared by the quality measures and the clean-up's sliver
// test, which the GPU engine runs too.
#pragma once

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

// q = (b + c - a)(c + a - b)(a + b - c) / (a b c) for side lengths a, b, c; 0 when degenerate.
MESHD_HD inline double radius_ratio_of_sides(double la, double lb, double lc) {
  const double denom = la * lb * lc;
  if (denom <= 0.0) return 0.0;
  const double q = (lb + lc - la) * (lc + la - lb) * (la + lb - lc) / denom;
  return q < 0.0 ? 0.0 : q;  // std::max(q, 0.0), NaN included
}

// The same for the triangle (a, b, c): la = |b - c|, lb = |c - a|, lc = |a - b|.
MESHD_HD inline double radius_ratio(Vec2 a, Vec2 b, Vec2 c) {
  return radius_ratio_of_sides(norm(b - c), norm(c - a), norm(a - b));
}

// The same for the triangle (a, b, c) taken in this order, but -1 when it is flat or turns
// clockwise: such triangles rank below every valid one (the worst-element optimisation).
MESHD_HD inline double oriented_radius_ratio(Vec2 a, Vec2 b, Vec2 c) {
  if (cross(b - a, c - a) <= 0.0) return -1.0;
  return radius_ratio(a, b, c);
}

}  // namespace meshd
