#include "core/delaunay/exact_predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace meshd {
namespace {
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;
Point to_cgal(Vec2 p) { return Point(p.x, p.y); }
}  // namespace

int orientation_sign(Vec2 a, Vec2 b, Vec2 c) {
  return static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c)));
}

int in_circle_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return static_cast<int>(
      CGAL::side_of_oriented_circle(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
}

}  // namespace meshd
