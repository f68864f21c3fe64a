#include "core/geometry3d/shape3d.h"

#include <cmath>

namespace meshd {
namespace {

// A rotation as a unit quaternion (w, v): composing two is one product, and it turns back into
// an axis and an angle without the sign ambiguities of a matrix.
struct Quaternion {
  double w = 1.0;
  Vec3 v;
};

Quaternion quaternion(const Similarity3& t) {
  // hypot rather than norm: an axis may be any non-zero finite vector, 1e-200 or 1e200 long.
  const double len = std::hypot(t.axis.x, t.axis.y, t.axis.z);
  if (t.angle == 0.0 || !(len > 0.0)) return {};
  const double s = std::sin(0.5 * t.angle) / len;
  return {std::cos(0.5 * t.angle), s * t.axis};
}

Quaternion product(const Quaternion& a, const Quaternion& b) {
  return {a.w * b.w - dot(a.v, b.v), a.w * b.v + b.w * a.v + cross(a.v, b.v)};
}

}  // namespace

Vec3 rotate(const Similarity3& t, Vec3 v) {
  // v' = v + 2 w (u x v) + 2 u x (u x v) for the unit quaternion (w, u).
  const Quaternion q = quaternion(t);
  const Vec3 uv = cross(q.v, v);
  return v + (2.0 * q.w) * uv + 2.0 * cross(q.v, uv);
}

Vec3 apply(const Similarity3& t, Vec3 p) { return t.scale * rotate(t, p) + t.offset; }

Similarity3 compose(const Similarity3& outer, const Similarity3& inner) {
  // outer(inner(p)) = so Ro (si Ri p + ti) + to = (so si) (Ro Ri) p + outer(ti)
  const Quaternion q = product(quaternion(outer), quaternion(inner));
  const double s = norm(q.v);
  Similarity3 t;
  t.scale = outer.scale * inner.scale;
  if (s > 0.0) {
    t.axis = (1.0 / s) * q.v;
    t.angle = 2.0 * std::atan2(s, q.w);
  }
  t.offset = apply(outer, inner.offset);
  return t;
}

}  // namespace meshd
