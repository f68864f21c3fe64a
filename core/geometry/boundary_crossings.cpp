#include "core/geometry/boundary_crossings.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/geometry/grid_box_crossings.h"

namespace meshd {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Curve parameters this far outside [0, 1] still count: a polygon vertex on another boundary.
constexpr double kParamSlack = 1e-12;
constexpr int kEllipseSamples = 1024;

// One piece of a primitive's boundary. Segment: a, b. Circle: center, r. Ellipse: center, semi
// axes ea, eb in its own frame, rotated by (cs, sn).
struct Curve {
  enum class Kind { kSegment, kCircle, kEllipse } kind = Kind::kSegment;
  int primitive = -1;
  Vec2 a, b;
  Vec2 center;
  double r = 0, ea = 0, eb = 0, cs = 1, sn = 0;
  Box bounds;
};

Vec2 perp(Vec2 v) { return {-v.y, v.x}; }

// Ellipse frame: world -> local and back.
Vec2 to_local(const Curve& e, Vec2 p) {
  const Vec2 d = p - e.center;
  return {e.cs * d.x + e.sn * d.y, -e.sn * d.x + e.cs * d.y};
}
Vec2 to_world(const Curve& e, Vec2 l) {
  return e.center + Vec2{e.cs * l.x - e.sn * l.y, e.sn * l.x + e.cs * l.y};
}

Curve segment(int prim, Vec2 a, Vec2 b) {
  Curve c;
  c.primitive = prim;
  c.a = a;
  c.b = b;
  c.bounds = {{std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)}};
  return c;
}

// The line n.p = offset (n unit) clipped to `box`; false when it misses the box.
bool clip_line(Vec2 n, double offset, const Box& box, Vec2& a, Vec2& b) {
  const Vec2 dir = perp(n), base = offset * n;
  double lo = -INFINITY, hi = INFINITY;
  const double p0[2] = {base.x, base.y}, d[2] = {dir.x, dir.y};
  const double mn[2] = {box.min.x, box.min.y}, mx[2] = {box.max.x, box.max.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (p0[k] < mn[k] || p0[k] > mx[k]) return false;
      continue;
    }
    double t0 = (mn[k] - p0[k]) / d[k], t1 = (mx[k] - p0[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) return false;  // unbounded box
  a = base + lo * dir;
  b = base + hi * dir;
  return true;
}

// The boundary curves of every primitive (parameter layout in program.h).
std::vector<Curve> curves_of(const Program& g, const Box& box) {
  std::vector<Curve> out;
  for (const Instruction& ins : g.code) {
    if (ins.primitive < 0) continue;
    const double* q = g.params.data() + ins.operand;
    const std::vector<double>& corners = g.primitives[ins.primitive].corners;
    switch (ins.op) {
      case Op::kBox:
      case Op::kPolygon: {
        const size_t n = corners.size() / 2;
        for (size_t i = 0; i < n; ++i) {
          const size_t j = (i + 1) % n;
          out.push_back(segment(ins.primitive, {corners[2 * i], corners[2 * i + 1]},
                                {corners[2 * j], corners[2 * j + 1]}));
        }
        break;
      }
      case Op::kHalfPlane: {
        Vec2 a, b;
        if (clip_line({q[0], q[1]}, q[2], box, a, b)) out.push_back(segment(ins.primitive, a, b));
        break;
      }
      case Op::kCircle: {
        Curve c;
        c.kind = Curve::Kind::kCircle;
        c.primitive = ins.primitive;
        c.center = {q[0], q[1]};
        c.r = q[2];
        c.bounds = {{q[0] - q[2], q[1] - q[2]}, {q[0] + q[2], q[1] + q[2]}};
        out.push_back(c);
        break;
      }
      case Op::kEllipse: {
        Curve c;
        c.kind = Curve::Kind::kEllipse;
        c.primitive = ins.primitive;
        c.center = {q[0], q[1]};
        c.ea = q[2];
        c.eb = q[3];
        c.cs = q[4];
        c.sn = q[5];
        const double wx = std::hypot(c.ea * c.cs, c.eb * c.sn),
                     wy = std::hypot(c.ea * c.sn, c.eb * c.cs);
        c.bounds = {{q[0] - wx, q[1] - wy}, {q[0] + wx, q[1] + wy}};
        out.push_back(c);
        break;
      }
      default:
        break;
    }
  }
  return out;
}

// An outward normal (any length) of the curve at p, a point on it.
Vec2 normal_at(const Curve& c, Vec2 p) {
  switch (c.kind) {
    case Curve::Kind::kSegment:
      return perp(c.b - c.a);
    case Curve::Kind::kCircle:
      return p - c.center;
    case Curve::Kind::kEllipse: {
      const Vec2 l = to_local(c, p);
      const Vec2 g{l.x / (c.ea * c.ea), l.y / (c.eb * c.eb)};
      return Vec2{c.cs * g.x - c.sn * g.y, c.sn * g.x + c.cs * g.y};
    }
  }
  return {};
}

// Implicit function of a circle or an ellipse: negative inside, zero on the curve.
double implicit(const Curve& c, Vec2 p) {
  if (c.kind == Curve::Kind::kCircle) {
    const Vec2 d = p - c.center;
    return dot(d, d) - c.r * c.r;
  }
  const Vec2 l = to_local(c, p);
  return (l.x / c.ea) * (l.x / c.ea) + (l.y / c.eb) * (l.y / c.eb) - 1.0;
}

bool in_param(double t) { return t >= -kParamSlack && t <= 1.0 + kParamSlack; }

void segment_segment(const Curve& s, const Curve& u, std::vector<Vec2>& out) {
  const Vec2 d1 = s.b - s.a, d2 = u.b - u.a, w = u.a - s.a;
  const double den = cross(d1, d2);
  if (std::fabs(den) <= 1e-14 * norm(d1) * norm(d2)) return;  // parallel: no single crossing
  const double t = cross(w, d2) / den, v = cross(w, d1) / den;
  if (in_param(t) && in_param(v)) out.push_back(s.a + t * d1);
}

// The crossings of segment a-b with the circle |p - c| = r, by the quadratic in the segment's
// parameter, in the form that loses no digits to cancellation.
void segment_circle(Vec2 a, Vec2 b, Vec2 c, double r, std::vector<double>& params) {
  const Vec2 d = b - a, f = a - c;
  const double A = dot(d, d), B = 2.0 * dot(f, d), C = dot(f, f) - r * r;
  const double disc = B * B - 4.0 * A * C;
  if (!(A > 0.0) || !(disc > 0.0)) return;  // no crossing, or a tangent
  const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  if (q != 0.0) {
    params.push_back(q / A);
    params.push_back(C / q);
  } else {
    params.push_back(std::sqrt(-C / A));
    params.push_back(-std::sqrt(-C / A));
  }
}

void segment_round(const Curve& s, const Curve& round, std::vector<Vec2>& out) {
  std::vector<double> params;
  if (round.kind == Curve::Kind::kCircle) {
    segment_circle(s.a, s.b, round.center, round.r, params);
  } else {
    // In the ellipse's frame scaled by its semi axes it is the unit circle; the segment's
    // parameter is the same in both frames (the map is affine).
    const Vec2 la = to_local(round, s.a), lb = to_local(round, s.b);
    segment_circle({la.x / round.ea, la.y / round.eb}, {lb.x / round.ea, lb.y / round.eb}, {0, 0},
                   1.0, params);
  }
  for (double t : params)
    if (in_param(t)) out.push_back(s.a + t * (s.b - s.a));
}

void circle_circle(const Curve& c1, const Curve& c2, std::vector<Vec2>& out) {
  const Vec2 d = c2.center - c1.center;
  const double dist = norm(d);
  if (!(dist > 0.0)) return;
  const double a = (c1.r * c1.r - c2.r * c2.r + dist * dist) / (2.0 * dist);
  const double h2 = c1.r * c1.r - a * a;
  if (!(h2 > 0.0)) return;  // apart, nested, or tangent
  const Vec2 e = (1.0 / dist) * d, mid = c1.center + a * e;
  const double h = std::sqrt(h2);
  out.push_back(mid + h * perp(e));
  out.push_back(mid - h * perp(e));
}

// The ellipse e against a circle or another ellipse `other`: sign changes of other's implicit
// function along e's angle, each bisected until the bracket stops shrinking.
void ellipse_round(const Curve& e, const Curve& other, std::vector<Vec2>& out) {
  auto at = [&](double t) { return to_world(e, {e.ea * std::cos(t), e.eb * std::sin(t)}); };
  double t0 = 0.0, f0 = implicit(other, at(0.0));
  for (int k = 1; k <= kEllipseSamples; ++k) {
    const double t1 = 2.0 * kPi * k / kEllipseSamples, f1 = implicit(other, at(t1));
    if ((f0 < 0.0) != (f1 < 0.0)) {
      double lo = t0, hi = t1, flo = f0;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        const double fm = implicit(other, at(mid));
        if ((fm < 0.0) == (flo < 0.0)) {
          lo = mid;
          flo = fm;
        } else {
          hi = mid;
        }
      }
      out.push_back(at(0.5 * (lo + hi)));
    }
    t0 = t1;
    f0 = f1;
  }
}

void intersect(const Curve& c1, const Curve& c2, std::vector<Vec2>& points) {
  using K = Curve::Kind;
  const Curve& a = c1.kind <= c2.kind ? c1 : c2;  // segment < circle < ellipse
  const Curve& b = c1.kind <= c2.kind ? c2 : c1;
  std::vector<Vec2> found;
  if (a.kind == K::kSegment && b.kind == K::kSegment)
    segment_segment(a, b, found);
  else if (a.kind == K::kSegment)
    segment_round(a, b, found);
  else if (a.kind == K::kCircle && b.kind == K::kCircle)
    circle_circle(a, b, found);
  else
    ellipse_round(b, a, found);
  const double min_sin = std::sin(kMinCrossingDegrees * kPi / 180.0);
  for (Vec2 p : found) {
    const Vec2 n1 = normal_at(a, p), n2 = normal_at(b, p);
    const double len = norm(n1) * norm(n2);
    if (len > 0.0 && std::fabs(cross(n1, n2)) >= min_sin * len) points.push_back(p);
  }
}

bool overlaps(const Box& a, const Box& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

}  // namespace

std::vector<Vec2> boundary_crossings(const Program& geometry, const Box& box) {
  // A point on the box's side (a half-plane's line along it) must not fall off by a rounding.
  const double slack = 1e-9 * std::hypot(box.max.x - box.min.x, box.max.y - box.min.y);
  const Box wide{{box.min.x - slack, box.min.y - slack}, {box.max.x + slack, box.max.y + slack}};
  const std::vector<Curve> curves = curves_of(geometry, wide);
  // A sweep over the curves' boxes in x: each pair whose boxes overlap is met once, from the one
  // that starts further left.
  std::vector<size_t> order(curves.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t i, size_t j) { return curves[i].bounds.min.x < curves[j].bounds.min.x; });
  std::vector<Vec2> points;
  for (size_t i = 0; i < order.size(); ++i) {
    const Curve& c = curves[order[i]];
    for (size_t j = i + 1; j < order.size(); ++j) {
      const Curve& d = curves[order[j]];
      if (d.bounds.min.x > c.bounds.max.x) break;
      if (d.primitive != c.primitive && overlaps(c.bounds, d.bounds)) intersect(c, d, points);
    }
  }
  for (const Instruction& ins : geometry.code)
    if (ins.op == Op::kGrid) grid_box_crossings(geometry, ins, points);
  std::vector<Vec2> inside;
  for (Vec2 p : points)
    if (p.x >= wide.min.x && p.x <= wide.max.x && p.y >= wide.min.y && p.y <= wide.max.y)
      inside.push_back(p);
  return inside;
}

}  // namespace meshd
