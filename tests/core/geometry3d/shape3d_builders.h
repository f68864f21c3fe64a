// Short builders for 3D geometry trees in tests.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/geometry3d/shape3d.h"

namespace meshd::testing {

inline Shape3 sphere(Vec3 c, double r, std::string name = "", std::string path = "") {
  return Shape3{Sphere{c, r}, std::move(name), std::move(path)};
}

inline Shape3 cuboid(Vec3 lo, Vec3 hi, std::string name = "", std::string path = "") {
  return Shape3{Cuboid{lo, hi}, std::move(name), std::move(path)};
}

inline Shape3 cylinder(Vec3 base, double r, double h, std::string path = "") {
  return Shape3{Cylinder{base, r, h}, "", std::move(path)};
}

inline Shape3 frustum(Vec3 base, double rb, double rt, double h, std::string path = "") {
  return Shape3{Frustum{base, rb, rt, h}, "", std::move(path)};
}

inline Shape3 torus(Vec3 c, double major, double minor, std::string path = "") {
  return Shape3{Torus{c, major, minor}, "", std::move(path)};
}

// The half-space dot(normal, p) <= offset.
inline Shape3 half_space(Vec3 normal, double offset, std::string path = "") {
  return Shape3{HalfSpace{normal, offset}, "", std::move(path)};
}

// The cube [lo, hi]^3 as 12 triangles turned outward (inward where `inward`).
inline Shape3 cube_polyhedron(double lo, double hi, bool inward = false, std::string path = "") {
  Polyhedron p;
  for (int k = 0; k < 8; ++k)
    p.vertices.push_back({k & 1 ? hi : lo, k & 2 ? hi : lo, k & 4 ? hi : lo});
  // Two triangles per face, counter-clockwise seen from outside.
  p.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  if (inward)
    for (auto& t : p.triangles) std::swap(t[1], t[2]);
  return Shape3{std::move(p), "", std::move(path)};
}

inline Shape3 csg3(CsgOp op, std::vector<Shape3> operands, std::string path = "") {
  return Shape3{Csg3{op, std::move(operands)}, "", std::move(path)};
}

inline Shape3 transformed3(Shape3 inner, const Similarity3& t, std::string path = "") {
  Transformed3 tr;
  tr.transform = t;
  tr.operand.push_back(std::move(inner));
  return Shape3{std::move(tr), "", std::move(path)};
}

}  // namespace meshd::testing
