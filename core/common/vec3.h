// A point or vector in space, in the request's length unit.
#pragma once

#include <cmath>

#include "core/common/hd.h"

namespace meshd {

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

MESHD_HD inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
MESHD_HD inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
MESHD_HD inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
MESHD_HD inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
MESHD_HD inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
MESHD_HD inline double norm(Vec3 a) { return sqrt(dot(a, a)); }
MESHD_HD inline bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// Axis-aligned box; empty when min > max in any coordinate.
struct Box3 {
  Vec3 min;
  Vec3 max;
};

}  // namespace meshd
