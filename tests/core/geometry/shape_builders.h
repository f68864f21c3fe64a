// Short builders for geometry trees in tests.
#pragma once

#include <functional>
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

// A distance grid of nx by ny samples of f, row by row from `origin`, `h` apart both ways.
inline Shape distance_grid(const std::function<double(Vec2)>& f, Vec2 origin, double h, uint32_t nx,
                           uint32_t ny, std::string name = "") {
  DistanceGrid g{origin, {h, h}, nx, ny, {}};
  g.values.reserve(size_t(nx) * ny);
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i)
      g.values.push_back(static_cast<float>(f({origin.x + i * h, origin.y + j * h})));
  return Shape{std::move(g), std::move(name), ""};
}

// The unit disk's distance |p| - 1 on a grid over [-1.5, 1.5]^2, h = 3 / (n - 1).
inline Shape disk_grid(uint32_t n, std::string name = "") {
  return distance_grid([](Vec2 p) { return norm(p) - 1.0; }, {-1.5, -1.5}, 3.0 / (n - 1), n, n,
                       std::move(name));
}

}  // namespace meshd::testing
