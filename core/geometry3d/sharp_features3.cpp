#include "core/geometry3d/sharp_features3.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/boundary_samples.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/spaced_points3.h"

namespace meshd {
namespace {

// Points closer than this (relative to the spacing) are one: the same corner reached from two
// primitives differs only by rounding.
constexpr double kMergeFraction = 1e-6;
// A feature point is on the boundary where |distance| <= kOnBoundaryFraction spacing, plus
// rounding in the point's own coordinates.
constexpr double kOnBoundaryFraction = 1e-9;
constexpr double kRoundingFraction = 1e-12;

Vec3 load(const double* q) { return {q[0], q[1], q[2]}; }

// Collects one primitive's candidate points, counting them against the limit before any is made.
class Sampler {
 public:
  Sampler(std::vector<Vec3>& out, double spacing) : out_(out), spacing_(spacing) {}

  void set_primitive(const std::string& path) { path_ = &path; }

  void corner(Vec3 p) {
    reserve(1.0);
    out_.push_back(p);
  }

  // The points strictly between a and b, at most `spacing` apart together with a and b.
  void segment(Vec3 a, Vec3 b) {
    const double n = std::ceil(norm(b - a) / spacing_);
    reserve(n - 1.0);
    for (int i = 1; i < static_cast<int>(n); ++i) out_.push_back(a + (i / n) * (b - a));
  }

  // The circle of radius r about c in the plane perpendicular to the unit vector a: at least
  // 3 points, with arcs (so chords) of at most `spacing` between neighbours.
  void circle(Vec3 c, Vec3 a, double r) {
    const double n = std::max(3.0, std::ceil(2.0 * std::numbers::pi * r / spacing_));
    reserve(n);
    // Any unit u perpendicular to a: the cross product with the coordinate axis a leans on least.
    const Vec3 e = std::fabs(a.x) <= std::fabs(a.y) && std::fabs(a.x) <= std::fabs(a.z)
                       ? Vec3{1, 0, 0}
                       : (std::fabs(a.y) <= std::fabs(a.z) ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    Vec3 u = cross(a, e);
    u = (1.0 / norm(u)) * u;
    const Vec3 v = cross(a, u);
    for (int i = 0; i < static_cast<int>(n); ++i) {
      const double t = 2.0 * std::numbers::pi * i / n;
      out_.push_back(c + (r * std::cos(t)) * u + (r * std::sin(t)) * v);
    }
  }

  // Points along the polyline `line` (a loop when `closed`: its last point joins its first) at
  // equal arc lengths at most `spacing` apart, its ends excluded (they are corners) unless it is a
  // loop, which gets at least 3.
  void polyline(const std::vector<Vec3>& line, bool closed) {
    std::vector<double> at(line.size(), 0.0);
    for (size_t i = 1; i < line.size(); ++i) at[i] = at[i - 1] + norm(line[i] - line[i - 1]);
    const double total = at.back() + (closed ? norm(line.front() - line.back()) : 0.0);
    const double n = std::max(closed ? 3.0 : 1.0, std::ceil(total / spacing_));
    reserve(n);
    size_t seg = 0;
    for (int i = closed ? 0 : 1; i < static_cast<int>(n); ++i) {
      const double want = total * i / n;
      while (seg + 1 < line.size() && at[seg + 1] < want) ++seg;
      const Vec3 a = line[seg], b = seg + 1 < line.size() ? line[seg + 1] : line.front();
      const double len = norm(b - a);
      out_.push_back(len > 0.0 ? a + ((want - at[seg]) / len) * (b - a) : a);
    }
  }

 private:
  void reserve(double n) {
    count_ += n;
    if (!(count_ <= static_cast<double>(kMaxSharpFeaturePoints))) {
      throw_invalid(*path_, "its sharp corners and edges need more than " +
                                std::to_string(kMaxSharpFeaturePoints) +
                                " fixed points at the mesh's edge length; make it smaller "
                                "relative to the edge length, or the edge length larger");
    }
  }

  std::vector<Vec3>& out_;
  double spacing_;
  const std::string* path_ = nullptr;
  double count_ = 0.0;
};

// A polyhedron's sharp edges (triangle_surface3.h) in chains: a corner where other than two sharp
// edges meet or where two meet at an angle, samples along each chain between corners (and along
// each loop without one), so that a finely tessellated sharp curve gets samples `spacing` apart
// rather than a node at each of its vertices.
void sample_sharp_edges(const TriangleSurface3& surface, Sampler& s) {
  std::unordered_map<int32_t, std::vector<int32_t>> next;  // sharp neighbours of each vertex
  for (const auto& e : surface.sharp_edges) {
    next[e[0]].push_back(e[1]);
    next[e[1]].push_back(e[0]);
  }
  const double straight_cos = -std::cos(kSharpSurfaceAngleDeg * std::numbers::pi / 180.0);
  const auto is_corner = [&](int32_t v) {
    const std::vector<int32_t>& n = next.at(v);
    if (n.size() != 2) return true;
    const Vec3 p = surface.vertices[v];
    const Vec3 a = surface.vertices[n[0]] - p, b = surface.vertices[n[1]] - p;
    return dot(a, b) > straight_cos * norm(a) * norm(b);  // turns by more than the sharp angle
  };
  std::unordered_map<uint64_t, char> used;
  const auto key = [](int32_t a, int32_t b) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(std::min(a, b))) << 32) |
           static_cast<uint32_t>(std::max(a, b));
  };
  // Follows the chain from corner-or-start `from` through `to` until a corner or back at `from`.
  const auto walk = [&](int32_t from, int32_t to) {
    std::vector<Vec3> line{surface.vertices[from]};
    int32_t prev = from, at = to;
    used[key(prev, at)] = 1;
    while (at != from && !is_corner(at)) {
      line.push_back(surface.vertices[at]);
      const std::vector<int32_t>& n = next.at(at);
      const int32_t after = n[0] == prev ? n[1] : n[0];
      prev = at;
      at = after;
      used[key(prev, at)] = 1;
    }
    if (at != from) line.push_back(surface.vertices[at]);
    s.polyline(line, at == from);
  };
  std::vector<int32_t> vertices;
  for (const auto& [v, n] : next) vertices.push_back(v);
  std::sort(vertices.begin(), vertices.end());  // the same points in the same order every time
  for (int32_t v : vertices) {
    if (!is_corner(v)) continue;
    s.corner(surface.vertices[v]);
    for (int32_t u : next.at(v))
      if (!used.contains(key(v, u))) walk(v, u);
  }
  for (int32_t v : vertices)  // loops without a corner
    for (int32_t u : next.at(v))
      if (!used.contains(key(v, u))) walk(v, u);
}

// The candidates of one primitive (program3d.h gives the layout of q).
void sample_primitive(const Program3& program, Op3 op, const double* q, Sampler& s,
                      double spacing) {
  switch (op) {
    case Op3::kExtrusion: {
      // The rims of both ends, and a vertical edge at each corner of the profile (its corners
      // as a plane mesh pins them, in its own units).
      const Vec3 o = load(q), u = load(q + 3), v = load(q + 6), w = load(q + 9);
      const double sc = q[12], h = q[13];
      const Program& profile = *program.profiles[static_cast<size_t>(q[18])];
      const Box box{{q[14], q[15]}, {q[16], q[17]}};
      const auto at = [&](Vec2 p, double z) { return o + sc * (p.x * u + p.y * v + z * w); };
      const std::vector<Vec2> corners = boundary_corners(profile, box);
      for (Vec2 c : corners) {
        s.corner(at(c, 0.0));
        s.corner(at(c, h));
        s.segment(at(c, 0.0), at(c, h));
      }
      for (Vec2 p : boundary_samples(profile, box, spacing / sc, corners)) {
        s.corner(at(p, 0.0));
        s.corner(at(p, h));
      }
      return;
    }
    case Op3::kRevolution: {
      // Each corner of the profile off the axis turns into a rim; on it, into an apex.
      const Vec3 o = load(q), a = load(q + 3);
      const double sc = q[6];
      const Program& profile = *program.profiles[static_cast<size_t>(q[10])];
      const Box box{{-q[7], q[8]}, {q[7], q[9]}};
      const ProgramView view = profile.view();
      const double tiny = 1e-9 * spacing / sc;
      for (Vec2 c : boundary_corners(profile, box)) {
        if (c.x < -tiny) continue;
        const Vec3 centre = o + (sc * c.y) * a;
        if (c.x > tiny) {
          s.circle(centre, a, sc * c.x);
          continue;
        }
        // On the axis: an apex unless the outline leaves it square to the axis (a flat end,
        // smooth once revolved), which the distance's slope across the axis just off it tells.
        const double dx = 1e-3 * spacing / sc, step = 0.1 * dx;
        const double slope =
            (eval_sdf(view, {c.x + dx + step, c.y}) - eval_sdf(view, {c.x + dx - step, c.y})) /
            (2 * step);
        if (std::fabs(slope) > 1e-3) s.corner(centre);
      }
      return;
    }
    case Op3::kCuboid: {
      const Vec3 c = load(q);
      const Vec3 axes[3] = {q[12] * load(q + 3), q[13] * load(q + 6), q[14] * load(q + 9)};
      // Corner k has sign bits (x, y, z) = (k & 1, k & 2, k & 4); an edge joins two corners
      // that differ in one bit.
      Vec3 corners[8];
      for (int k = 0; k < 8; ++k) {
        corners[k] = c + (k & 1 ? 1.0 : -1.0) * axes[0] + (k & 2 ? 1.0 : -1.0) * axes[1] +
                     (k & 4 ? 1.0 : -1.0) * axes[2];
        s.corner(corners[k]);
      }
      for (int k = 0; k < 8; ++k)
        for (int bit = 1; bit < 8; bit <<= 1)
          if (!(k & bit)) s.segment(corners[k], corners[k | bit]);
      return;
    }
    case Op3::kCylinder: {
      const Vec3 c = load(q), a = load(q + 3);
      s.circle(c - q[7] * a, a, q[6]);
      s.circle(c + q[7] * a, a, q[6]);
      return;
    }
    case Op3::kFrustum: {
      const Vec3 base = load(q), a = load(q + 3), top = base + q[8] * a;
      for (const auto& [centre, r] : {std::pair{base, q[6]}, std::pair{top, q[7]}}) {
        if (r > 0.0)
          s.circle(centre, a, r);
        else
          s.corner(centre);  // a cone's apex
      }
      return;
    }
    case Op3::kPolyhedron:
      sample_sharp_edges(*program.surfaces[static_cast<size_t>(q[6])], s);
      return;
    default:  // spheres, tori and half-spaces are smooth
      return;
  }
}

}  // namespace

std::vector<Vec3> sharp_features3(const Program3& program, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    throw Error(ErrorCode::kInternal, "",
                "sharp_features3 needs a finite spacing > 0 (got " + std::to_string(spacing) + ")");
  }
  std::vector<Vec3> candidates;
  Sampler sampler(candidates, spacing);
  for (const Instruction3& ins : program.code) {
    if (ins.primitive < 0) continue;
    sampler.set_primitive(program.primitives[ins.primitive].path);
    sample_primitive(program, ins.op, program.params.data() + ins.operand, sampler, spacing);
  }

  std::vector<Vec3> out;
  SpacedPoints3 kept(kMergeFraction * spacing);
  const Program3View view = program.view();
  for (Vec3 p : candidates) {
    const double size = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    const double tol = kOnBoundaryFraction * spacing + kRoundingFraction * size;
    if (std::fabs(eval_sdf3(view, p)) <= tol && !kept.near(p)) {
      kept.add(p);
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace meshd
