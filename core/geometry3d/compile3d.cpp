#include "core/geometry3d/compile3d.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <variant>

#include "core/common/error.h"
#include "core/geometry/bounds.h"
#include "core/geometry/compile.h"
#include "core/geometry3d/triangle_surface3.h"

namespace meshd {
namespace {

std::string shown(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string shown(Vec3 v) { return "(" + shown(v.x) + ", " + shown(v.y) + ", " + shown(v.z) + ")"; }

double positive(double v, const std::string& field) {
  if (!(v > 0.0) || !std::isfinite(v))
    throw_invalid(field, "must be finite and > 0 (got " + shown(v) + ")");
  return v;
}

double non_negative(double v, const std::string& field) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw_invalid(field, "must be finite and >= 0 (got " + shown(v) + ")");
  return v;
}

double finite(double v, const std::string& field) {
  if (!std::isfinite(v)) throw_invalid(field, "must be finite (got " + shown(v) + ")");
  return v;
}

Vec3 finite(Vec3 v, const std::string& field) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw_invalid(field, "must be finite in every coordinate (got " + shown(v) + ")");
  return v;
}

// hypot rather than norm: a normal or an axis may be any non-zero finite vector.
double length(Vec3 v) { return std::hypot(v.x, v.y, v.z); }

const char* csg_name(CsgOp op) {
  switch (op) {
    case CsgOp::kUnion:
      return "union";
    case CsgOp::kIntersection:
      return "intersection";
    default:
      return "difference";
  }
}

// Emits postfix code for one tree, keeping track of how deep the value stack gets.
class Emitter3 {
 public:
  explicit Emitter3(Program3& program) : program_(program) {}

  // Emits `shape` under the accumulated transform; returns the stack slots it needs.
  int emit(const Shape3& shape, const Similarity3& t) {
    const int need =
        std::visit([&](const auto& node) { return emit_node(shape, node, t); }, shape.node);
    if (need > kMaxProgram3Stack) {
      throw_invalid(shape.path, "the tree is too deep to evaluate (needs " + std::to_string(need) +
                                    " stack slots, at most " + std::to_string(kMaxProgram3Stack) +
                                    ")");
    }
    return need;
  }

 private:
  // Transforms fold into the parameters, so that a chain of them can take a valid primitive out
  // of the range of doubles or shrink its size to 0; and the evaluator squares coordinates, so
  // beyond kMaxCoordinate every distance would read inf. `values` are the folded parameters,
  // `sizes` the lengths among them that must stay positive.
  static constexpr double kMaxCoordinate = 1e150;

  static void check_folded(const Shape3& shape, std::initializer_list<double> values,
                           std::initializer_list<double> sizes) {
    const std::string rule =
        "; coordinates and lengths, after the scale factors multiplied and the offsets added "
        "along its path, must be finite, within +-1e150, and lengths > 0";
    for (double v : values) {
      if (!(std::fabs(v) <= kMaxCoordinate)) {
        throw_invalid(shape.path,
                      "a coordinate or length of this shape, after the transforms "
                      "above it, is " +
                          shown(v) + rule);
      }
    }
    for (double v : sizes) {
      if (!(v > 0.0))
        throw_invalid(shape.path, "its size, after the transforms above it, is 0" + rule);
    }
  }

  int push(const Shape3& shape, Op3 op, std::initializer_list<double> params, const char* kind) {
    PrimitiveInfo3 info;
    info.name = shape.name.empty() ? kind + std::to_string(++default_index_[kind]) : shape.name;
    info.path = shape.path;
    const auto offset = static_cast<uint32_t>(program_.params.size());
    program_.params.insert(program_.params.end(), params);
    program_.code.push_back({op, offset, static_cast<int32_t>(program_.primitives.size())});
    program_.primitives.push_back(std::move(info));
    return 1;
  }

  int emit_node(const Shape3& s, const Sphere& sp, const Similarity3& t) {
    const std::string p = s.path + ".sphere";
    const Vec3 c = apply(t, finite(sp.center, p + ".center"));
    const double r = t.scale * positive(sp.radius, p + ".radius");
    check_folded(s, {c.x, c.y, c.z, r}, {r});
    return push(s, Op3::kSphere, {c.x, c.y, c.z, r}, "sphere");
  }

  int emit_node(const Shape3& s, const Cuboid& b, const Similarity3& t) {
    const std::string p = s.path + ".cuboid";
    finite(b.min, p + ".min");
    finite(b.max, p + ".max");
    if (!(b.max.x > b.min.x && b.max.y > b.min.y && b.max.z > b.min.z)) {
      throw_invalid(p + ".max", "must exceed min in every coordinate (got min " + shown(b.min) +
                                    ", max " + shown(b.max) + ")");
    }
    const Vec3 c = apply(t, 0.5 * (b.min + b.max));
    const Vec3 h = (0.5 * t.scale) * (b.max - b.min);
    const Vec3 u = rotate(t, {1, 0, 0}), v = rotate(t, {0, 1, 0}), w = rotate(t, {0, 0, 1});
    check_folded(s, {c.x, c.y, c.z, h.x, h.y, h.z}, {h.x, h.y, h.z});
    return push(s, Op3::kCuboid,
                {c.x, c.y, c.z, u.x, u.y, u.z, v.x, v.y, v.z, w.x, w.y, w.z, h.x, h.y, h.z},
                "cuboid");
  }

  int emit_node(const Shape3& s, const Cylinder& cy, const Similarity3& t) {
    const std::string p = s.path + ".cylinder";
    const Vec3 base = finite(cy.base_center, p + ".base_center");
    const double height = positive(cy.height, p + ".height");
    const double r = t.scale * positive(cy.radius, p + ".radius");
    const double hh = 0.5 * t.scale * height;
    const Vec3 c = apply(t, base + Vec3{0, 0, 0.5 * height});
    const Vec3 a = rotate(t, {0, 0, 1});
    check_folded(s, {c.x, c.y, c.z, r, hh}, {r, hh});
    return push(s, Op3::kCylinder, {c.x, c.y, c.z, a.x, a.y, a.z, r, hh}, "cylinder");
  }

  int emit_node(const Shape3& s, const Frustum& f, const Similarity3& t) {
    const std::string p = s.path + ".frustum";
    const Vec3 base = apply(t, finite(f.base_center, p + ".base_center"));
    const double rb = t.scale * non_negative(f.bottom_radius, p + ".bottom_radius");
    const double rt = t.scale * non_negative(f.top_radius, p + ".top_radius");
    if (f.bottom_radius == 0.0 && f.top_radius == 0.0)
      throw_invalid(p + ".top_radius", "must be > 0 where bottom_radius is 0 (got both 0)");
    const double h = t.scale * positive(f.height, p + ".height");
    const Vec3 a = rotate(t, {0, 0, 1});
    check_folded(s, {base.x, base.y, base.z, rb, rt, h}, {h, rb + rt});
    return push(s, Op3::kFrustum, {base.x, base.y, base.z, a.x, a.y, a.z, rb, rt, h}, "frustum");
  }

  int emit_node(const Shape3& s, const Torus& to, const Similarity3& t) {
    const std::string p = s.path + ".torus";
    const Vec3 c = apply(t, finite(to.center, p + ".center"));
    const double minor = positive(to.minor_radius, p + ".minor_radius");
    if (!(to.major_radius > minor) || !std::isfinite(to.major_radius)) {
      throw_invalid(p + ".major_radius", "must be finite and exceed minor_radius " + shown(minor) +
                                             " (got " + shown(to.major_radius) + ")");
    }
    const double big = t.scale * to.major_radius, small = t.scale * minor;
    const Vec3 a = rotate(t, {0, 0, 1});
    check_folded(s, {c.x, c.y, c.z, big, small}, {small});
    return push(s, Op3::kTorus, {c.x, c.y, c.z, a.x, a.y, a.z, big, small}, "torus");
  }

  int emit_node(const Shape3& s, const HalfSpace& hs, const Similarity3& t) {
    // {n.x <= c} maps under x' = s R x + t to {R n . x' <= s c + R n . t}; store the unit normal.
    const std::string p = s.path + ".half_space";
    const Vec3 normal = finite(hs.normal, p + ".normal");
    const double len = length(normal);
    if (!(len > 0.0))
      throw_invalid(p + ".normal", "must be non-zero (got (0, 0, 0)); it need not be unit length");
    const Vec3 n = rotate(t, (1.0 / len) * normal);
    const double c = t.scale * (finite(hs.offset, p + ".offset") / len) + dot(n, t.offset);
    check_folded(s, {c}, {});
    return push(s, Op3::kHalfSpace, {n.x, n.y, n.z, c}, "half_space");
  }

  // The profile compiled (its errors name its own fields) and its box, which must be bounded.
  int add_profile(const Shape& profile, const std::string& path, Box& box) {
    auto compiled = std::make_shared<const Program>(compile_geometry(profile));
    box = program_bounds(*compiled);
    if (!is_bounded(box) || is_empty(box)) {
      throw_invalid(path, std::string("must be ") + (is_empty(box) ? "non-empty" : "bounded") +
                              ": cut a half-plane off with a bounded shape");
    }
    program_.profiles.push_back(std::move(compiled));
    return static_cast<int>(program_.profiles.size()) - 1;
  }

  int emit_node(const Shape3& s, const Extrusion& e, const Similarity3& t) {
    const std::string p = s.path + ".extrusion";
    const double h = positive(e.height, p + ".height");
    Box box;
    const int k = add_profile(e.profile, p + ".profile", box);
    const Vec3 o = apply(t, {0, 0, 0}), u = rotate(t, {1, 0, 0}), v = rotate(t, {0, 1, 0}),
               w = rotate(t, {0, 0, 1});
    check_folded(s,
                 {o.x, o.y, o.z, t.scale * h, t.scale * box.min.x, t.scale * box.max.x,
                  t.scale * box.min.y, t.scale * box.max.y},
                 {t.scale * h});
    return push(s, Op3::kExtrusion,
                {o.x, o.y, o.z, u.x, u.y, u.z, v.x, v.y, v.z, w.x, w.y, w.z, t.scale, h, box.min.x,
                 box.min.y, box.max.x, box.max.y, static_cast<double>(k)},
                "extrusion");
  }

  int emit_node(const Shape3& s, const Revolution& r, const Similarity3& t) {
    const std::string p = s.path + ".revolution";
    Box box;
    const int k = add_profile(r.profile, p + ".profile", box);
    if (!(box.max.x > 0.0)) {
      throw_invalid(p + ".profile", "must reach x > 0 (its part at x >= 0 is revolved; got x <= " +
                                        shown(box.max.x) + ")");
    }
    // An edge lying on the axis would count as a surface, so that the distance inside near the
    // axis would be far too small; a profile symmetric about the axis has none.
    if (box.min.x >= 0.0 && box.min.x <= 1e-9 * box.max.x) {
      throw_invalid(p + ".profile",
                    "touches the axis (x = 0) from one side, so its edge there would count as a "
                    "surface; to reach the axis, make the profile symmetric about it (e.g. a "
                    "rectangle from x = -r to r)");
    }
    const Vec3 o = apply(t, {0, 0, 0}), a = rotate(t, {0, 0, 1});
    check_folded(s, {o.x, o.y, o.z, t.scale * box.max.x, t.scale * box.min.y, t.scale * box.max.y},
                 {t.scale * box.max.x});
    return push(s, Op3::kRevolution,
                {o.x, o.y, o.z, a.x, a.y, a.z, t.scale, box.max.x, box.min.y, box.max.y,
                 static_cast<double>(k)},
                "revolution");
  }

  int emit_node(const Shape3& s, const Polyhedron& poly, const Similarity3& t) {
    const std::string p = s.path + ".polyhedron";
    std::vector<Vec3> world;
    world.reserve(poly.vertices.size());
    for (size_t i = 0; i < poly.vertices.size(); ++i) {
      const Vec3 v = apply(t, finite(poly.vertices[i], p + ".vertices[" + std::to_string(i) + "]"));
      check_folded(s, {v.x, v.y, v.z}, {});
      world.push_back(v);
    }
    auto surface = std::make_shared<const TriangleSurface3>(
        build_triangle_surface3(std::move(world), poly.triangles, p));
    const Box3 b = surface->box;
    program_.surfaces.push_back(std::move(surface));
    const auto k = static_cast<double>(program_.surfaces.size() - 1);
    return push(s, Op3::kPolyhedron, {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z, k},
                "polyhedron");
  }

  // Left fold: a, b, op, c, op, ... keeps one accumulated value on the stack; a difference
  // negates each subtrahend before its max.
  int emit_node(const Shape3& s, const Csg3& csg, const Similarity3& t) {
    const auto& ops = csg.operands;
    if (ops.empty()) {
      throw_invalid(s.path + "." + csg_name(csg.op) + ".shapes",
                    "must hold at least one shape (got none)");
    }
    int need = 0;
    for (size_t i = 0; i < ops.size(); ++i) {
      need = std::max(need, (i == 0 ? 0 : 1) + emit(ops[i], t));
      if (i == 0) continue;
      if (csg.op == CsgOp::kDifference) program_.code.push_back({Op3::kNegate, 0, -1});
      const Op3 op = csg.op == CsgOp::kUnion ? Op3::kMin : Op3::kMax;
      program_.code.push_back({op, 0, -1});
    }
    return need;
  }

  int emit_node(const Shape3& s, const Transformed3& tr, const Similarity3& t) {
    const std::string p = s.path + ".transform";
    const Similarity3& own = tr.transform;
    positive(own.scale, p + ".scale");
    finite(own.axis, p + ".axis");
    finite(own.angle, p + ".angle");
    finite(own.offset, p + ".offset");
    if (own.angle != 0.0 && !(length(own.axis) > 0.0))
      throw_invalid(p + ".axis", "must be non-zero where angle is not 0 (got (0, 0, 0))");
    if (tr.operand.size() != 1) {
      throw_invalid(p + ".shape",
                    "required: exactly one shape (got " + std::to_string(tr.operand.size()) + ")");
    }
    return emit(tr.operand.front(), compose(t, own));
  }

  Program3& program_;
  std::map<std::string, int> default_index_;
};

}  // namespace

Program3 compile_geometry3(const Shape3& root) {
  Program3 program;
  program.root_path = root.path;
  Emitter3(program).emit(root, Similarity3{});
  for (const auto& profile : program.profiles) program.profile_views->push_back(profile->view());
  for (const auto& surface : program.surfaces) program.surface_views->push_back(surface->view());
  return program;
}

}  // namespace meshd
