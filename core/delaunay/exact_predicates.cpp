#include "core/delaunay/exact_predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace meshd {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
Kernel::Point_2 to_cgal(Vec2 p) { return {p.x, p.y}; }
Kernel::Point_3 to_cgal(Vec3 p) { return {p.x, p.y, p.z}; }
}  // namespace

int orientation_sign(Vec2 a, Vec2 b, Vec2 c) {
  return static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c)));
}

int in_circle_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return static_cast<int>(
      CGAL::side_of_oriented_circle(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
}

// CGAL's orientation is positive when d lies on the positive side of the plane of a, b, c,
// which is this convention's; its side of the oriented sphere is positive on the sphere's
// positive side, its inside for a positively oriented tetrahedron.
int orientation3_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  return static_cast<int>(CGAL::orientation(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
}

int in_sphere_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 e) {
  return static_cast<int>(
      CGAL::side_of_oriented_sphere(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d), to_cgal(e)));
}

}  // namespace meshd
