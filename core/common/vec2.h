// A point or vector in the plane, in the request's length unit.
#pragma once

#include <cmath>

#include "core/common/hd.h"

namespace meshd {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

MESHD_HD inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
MESHD_HD inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
MESHD_HD inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
MESHD_HD inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
MESHD_HD inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
MESHD_HD inline double norm(Vec2 a) { return sqrt(dot(a, a)); }
MESHD_HD inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

// Axis-aligned box; empty when min > max in either coordinate.
struct Box {
  Vec2 min;
  Vec2 max;
};

}  // namespace meshd
