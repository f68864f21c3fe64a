// Short builders for geometry trees in tests.
#pragma once

#include <string>
#include <vector>

#include "core/geometry/shape.h"

namespace meshd::testing {

inline Shape csg(CsgOp op, std::vector<Shape> operands, std::string path = "") {
  return Shape{Csg{op, std::move(operands)}, "", std::move(path)};
}

inline Shape transformed(Shape inner, double scale, double angle, Vec2 offset) {
  Transformed t;
  t.transform = {scale, angle, offset};
  t.operand.push_back(std::move(inner));
  return Shape{std::move(t), "", ""};
}

inline Shape circle(Vec2 c, double r, std::string name = "") {
  return Shape{Circle{c, r}, std::move(name), ""};
}

inline Shape rectangle(Vec2 lo, Vec2 hi, std::string name = "") {
  return Shape{Rectangle{lo, hi}, std::move(name), ""};
}

inline Shape ellipse(Vec2 c, double a, double b) { return Shape{Ellipse{c, a, b}, "", ""}; }

// The half-plane dot(normal, p) <= offset.
inline Shape half_plane(Vec2 normal, double offset, std::string name = "") {
  return Shape{HalfPlane{normal, offset}, std::move(name), ""};
}

}  // namespace meshd::testing
