#include "core/geometry/compile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <type_traits>

#include "core/common/error.h"
#include "core/geometry/bounds.h"
#include "core/geometry/regular_grid.h"

namespace meshd {
namespace {

// Below these sizes a plain walk over every edge or operand costs less than the tree's.
constexpr size_t kIndexedPolygonMinVertices = 64;
constexpr size_t kIndexedUnionMinOperands = 8;
constexpr uint32_t kEdgesPerLeaf = 8;

// Emits postfix code for one tree, keeping track of how deep the value stack gets.
class Emitter {
 public:
  explicit Emitter(Program& program) : program_(program) {}

  // Emits `shape` under the accumulated transform; returns the stack slots it needs.
  int emit(const Shape& shape, const Similarity& t) {
    const int need =
        std::visit([&](const auto& node) { return emit_node(shape, node, t); }, shape.node);
    if (need > kMaxProgramStack) {
      throw_invalid(shape.path, "the tree is too deep to evaluate (needs " + std::to_string(need) +
                                    " stack slots, at most " + std::to_string(kMaxProgramStack) +
                                    ")");
    }
    return need;
  }

 private:
  // Transforms fold into the parameters, so that a chain of them can take a valid primitive out
  // of the range of doubles (two nested scales by 1e300 give an infinite radius) or shrink its
  // size to 0 (two by 1e-300). And the evaluators square coordinates: beyond kMaxCoordinate the
  // squares overflow and every distance reads inf (a disk of radius 1e200 looked empty).
  // `values` are the folded parameters, `sizes` the lengths among them that must stay positive.
  static constexpr double kMaxCoordinate = 1e150;

  static void check_folded(const Shape& shape, std::initializer_list<double> values,
                           std::initializer_list<double> sizes = {}) {
    const std::string rule =
        "; coordinates and lengths, after the scale factors multiplied and the offsets added "
        "along its path, must be finite, within +-1e150, and lengths > 0";
    for (double v : values) {
      if (std::fabs(v) <= kMaxCoordinate) continue;
      char shown[32];
      std::snprintf(shown, sizeof shown, "%g", v);
      throw_invalid(shape.path, std::string("a coordinate or length of this shape, after the ") +
                                    "transforms above it, is " + shown + rule);
    }
    for (double v : sizes) {
      if (!(v > 0))
        throw_invalid(shape.path, "its size, after the transforms above it, is 0" + rule);
    }
  }

  int push_primitive(const Shape& shape, Op op, std::initializer_list<double> params,
                     const char* kind, std::vector<double> corners = {}) {
    check_folded(shape, params);
    for (double v : corners) check_folded(shape, {v});
    PrimitiveInfo info;
    info.name = shape.name.empty() ? kind + std::to_string(++default_index_[kind]) : shape.name;
    info.path = shape.path;
    info.corners = std::move(corners);
    const auto offset = static_cast<uint32_t>(program_.params.size());
    program_.params.insert(program_.params.end(), params);
    program_.code.push_back({op, offset, static_cast<int32_t>(program_.primitives.size())});
    program_.primitives.push_back(std::move(info));
    return 1;
  }

  int emit_node(const Shape& s, const Circle& c, const Similarity& t) {
    const Vec2 center = apply(t, c.center);
    check_folded(s, {}, {t.scale * c.radius});
    return push_primitive(s, Op::kCircle, {center.x, center.y, t.scale * c.radius}, "circle");
  }

  int emit_node(const Shape& s, const Rectangle& r, const Similarity& t) {
    const Vec2 center = apply(t, 0.5 * (r.min + r.max));
    const double hx = 0.5 * t.scale * (r.max.x - r.min.x), hy = 0.5 * t.scale * (r.max.y - r.min.y);
    check_folded(s, {}, {hx, hy});
    std::vector<double> corners;
    for (Vec2 v : {r.min, Vec2{r.max.x, r.min.y}, r.max, Vec2{r.min.x, r.max.y}}) {
      const Vec2 w = apply(t, v);
      corners.insert(corners.end(), {w.x, w.y});
    }
    return push_primitive(s, Op::kBox,
                          {center.x, center.y, hx, hy, std::cos(t.angle), std::sin(t.angle)},
                          "rectangle", std::move(corners));
  }

  int emit_node(const Shape& s, const Ellipse& e, const Similarity& t) {
    const Vec2 center = apply(t, e.center);
    check_folded(s, {}, {t.scale * e.semi_axis_x, t.scale * e.semi_axis_y});
    return push_primitive(s, Op::kEllipse,
                          {center.x, center.y, t.scale * e.semi_axis_x, t.scale * e.semi_axis_y,
                           std::cos(t.angle), std::sin(t.angle)},
                          "ellipse");
  }

  int emit_node(const Shape& s, const HalfPlane& h, const Similarity& t) {
    // {n.p <= c} maps to {R n . p' <= scale c + R n . offset}; store the unit normal.
    const double len = std::hypot(h.normal.x, h.normal.y);  // norm() over- or underflows
    const double cs = std::cos(t.angle), sn = std::sin(t.angle);
    const Vec2 n{(cs * h.normal.x - sn * h.normal.y) / len,
                 (sn * h.normal.x + cs * h.normal.y) / len};
    const double c = t.scale * h.offset / len + dot(n, t.offset);
    return push_primitive(s, Op::kHalfPlane, {n.x, n.y, c}, "half_plane");
  }

  int emit_node(const Shape& s, const Polygon& poly, const Similarity& t) {
    const auto offset = static_cast<uint32_t>(program_.params.size());
    std::vector<double> corners;
    corners.reserve(2 * poly.vertices.size());
    for (Vec2 v : poly.vertices) {
      const Vec2 w = apply(t, v);
      check_folded(s, {w.x, w.y});
      corners.insert(corners.end(), {w.x, w.y});
    }
    PrimitiveInfo info;
    info.name = s.name.empty() ? "polygon" + std::to_string(++default_index_["polygon"]) : s.name;
    info.path = s.path;
    program_.params.push_back(static_cast<double>(poly.vertices.size()));
    program_.params.insert(program_.params.end(), corners.begin(), corners.end());
    program_.params.push_back(signed_area(poly.vertices) >= 0.0 ? 1.0 : -1.0);
    const uint32_t bvh =
        poly.vertices.size() >= kIndexedPolygonMinVertices ? index_edges(corners) : kNoBvh;
    info.corners = std::move(corners);
    program_.code.push_back(
        {Op::kPolygon, offset, static_cast<int32_t>(program_.primitives.size()), bvh});
    program_.primitives.push_back(std::move(info));
    return 1;
  }

  // A grid's samples cannot move, so it keeps its own frame and the similarity that places it
  // follows its header (program.h); the evaluator maps each point into the grid's frame
  // (grid_sdf.cuh). Its box's corners, where they lie on the final boundary, are the domain's.
  int emit_node(const Shape& s, const DistanceGrid& g, const Similarity& t) {
    const Vec2 far{g.origin.x + (g.nx - 1) * g.spacing.x, g.origin.y + (g.ny - 1) * g.spacing.y};
    check_folded(s, {t.offset.x, t.offset.y}, {t.scale * g.spacing.x, t.scale * g.spacing.y});
    std::vector<double> corners;
    for (Vec2 v : {g.origin, Vec2{far.x, g.origin.y}, far, Vec2{g.origin.x, far.y}}) {
      const Vec2 w = apply(t, v);
      check_folded(s, {w.x, w.y});
      corners.insert(corners.end(), {w.x, w.y});
    }
    PrimitiveInfo info;
    info.name =
        s.name.empty() ? "distance_grid" + std::to_string(++default_index_["grid"]) : s.name;
    info.path = s.path;
    info.corners = std::move(corners);
    const uint32_t offset = append_grid(program_, g.origin, g.spacing, g.nx, g.ny, g.values.data());
    program_.params.insert(program_.params.end(),
                           {t.offset.x, t.offset.y, std::cos(t.angle), std::sin(t.angle), t.scale});
    program_.code.push_back({Op::kGrid, offset, static_cast<int32_t>(program_.primitives.size())});
    program_.primitives.push_back(std::move(info));
    return 1;
  }

  // Twice the signed area (shoelace): positive for a counter-clockwise polygon.
  static double signed_area(const std::vector<Vec2>& v) {
    double sum = 0.0;
    for (size_t i = 1; i + 1 < v.size(); ++i) sum += cross(v[i] - v[0], v[i + 1] - v[0]);
    return sum;
  }

  // A tree whose leaves are runs of kEdgesPerLeaf consecutive edges of the polygon `xy`
  // (#V by 2, flattened): neighbouring edges lie close, so a run makes a tight box.
  uint32_t index_edges(const std::vector<double>& xy) {
    const auto n = static_cast<uint32_t>(xy.size() / 2);
    std::vector<BvhItem> runs;
    for (uint32_t first = 0; first < n; first += kEdgesPerLeaf) {
      const uint32_t last = std::min(n, first + kEdgesPerLeaf);
      Box b{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
      for (uint32_t k = first; k <= last; ++k) {  // the run's vertices and its last edge's end
        const uint32_t v = k % n;
        b = {{std::min(b.min.x, xy[2 * v]), std::min(b.min.y, xy[2 * v + 1])},
             {std::max(b.max.x, xy[2 * v]), std::max(b.max.y, xy[2 * v + 1])}};
      }
      runs.push_back({b, first, last});
    }
    return build_bvh(std::move(runs), program_.nodes);
  }

  // Left fold: a, b, op, c, op, ... keeps one accumulated value on the stack. A union of many
  // operands gets an index in front of its fold; a difference of many subtrahends is emitted
  // as a minus the union of the rest, max(a, -min(b, c, ...)), which has the same value as the
  // fold max(max(a, -b), -c) ... and lets that union be indexed too.
  int emit_node(const Shape&, const Csg& csg, const Similarity& t) {
    const auto& ops = csg.operands;
    const bool many = ops.size() >= kIndexedUnionMinOperands;
    if (csg.op == CsgOp::kUnion && many) return emit_indexed_union(ops.begin(), ops.end(), t);
    if (csg.op == CsgOp::kDifference && ops.size() > kIndexedUnionMinOperands) {
      const int base = emit(ops.front(), t);
      const int rest = 1 + emit_indexed_union(ops.begin() + 1, ops.end(), t);
      program_.code.push_back({Op::kNegate, 0, -1});
      program_.code.push_back({Op::kMax, 0, -1});
      return std::max(base, rest);
    }
    int need = 0;
    for (size_t i = 0; i < ops.size(); ++i) {
      need = std::max(need, (i == 0 ? 0 : 1) + emit(ops[i], t));
      if (i == 0) continue;
      if (csg.op == CsgOp::kDifference) program_.code.push_back({Op::kNegate, 0, -1});
      const Op op = csg.op == CsgOp::kUnion ? Op::kMin : Op::kMax;
      program_.code.push_back({op, 0, -1});
    }
    return need;
  }

  // The union of [first, last): a kUnionIndexed instruction, then the plain fold, with a tree
  // over the operands' instruction ranges and their distance-bound boxes (bounds.h).
  int emit_indexed_union(std::vector<Shape>::const_iterator first,
                         std::vector<Shape>::const_iterator last, const Similarity& t) {
    const auto head = static_cast<uint32_t>(program_.code.size());
    program_.code.push_back({Op::kUnionIndexed, 0, -1});
    std::vector<BvhItem> operands;
    int need = 0;
    bool shallow = true;
    for (auto it = first; it != last; ++it) {
      const auto begin = static_cast<uint32_t>(program_.code.size());
      const int own = emit(*it, t);
      shallow = shallow && own <= kMaxIndexedOperandStack;
      need = std::max(need, (it == first ? 0 : 1) + own);
      const auto end = static_cast<uint32_t>(program_.code.size());
      operands.push_back({distance_bound_box(program_, begin, end), begin, end});
      if (it != first) program_.code.push_back({Op::kMin, 0, -1});
    }
    program_.code[head].operand = static_cast<uint32_t>(program_.code.size());
    if (shallow) program_.code[head].bvh = build_bvh(std::move(operands), program_.nodes);
    return need;
  }

  int emit_node(const Shape&, const Transformed& tr, const Similarity& t) {
    return emit(tr.operand.at(0), compose(t, tr.transform));
  }

  Program& program_;
  std::map<std::string, int> default_index_;
};

}  // namespace

Program compile_geometry(const Shape& root) {
  Program program;
  Emitter(program).emit(root, Similarity{});
  return program;
}

SizeProgram compile_size_field(const SizeFieldSpec& spec) {
  SizeProgram out;
  Emitter emitter(out.shapes);
  for (const auto& term : spec.terms) {
    if (const auto* u = std::get_if<UniformSize>(&term)) {
      out.terms.push_back({u->value, 0.0, u->value, 0, 0});
      continue;
    }
    if (const auto* g = std::get_if<GridSize>(&term)) {
      // Bilinear values stay within the samples' range: that range is the term's bounds.
      const SizeRange range = size_term_range(term);
      const uint32_t header =
          append_grid(out.shapes, g->origin, g->spacing, g->nx, g->ny, g->values.data());
      out.terms.push_back({range.low, 0.0, range.high, 0, 0, header, g->scale});
      continue;
    }
    if (std::holds_alternative<FeatureSize>(term)) {
      throw Error(ErrorCode::kInternal, "size.terms",
                  "a feature-size term reached the compiler unsampled (sampled_size_field)");
    }
    const auto& d = std::get<DistanceSize>(term);
    const auto begin = static_cast<uint32_t>(out.shapes.code.size());
    emitter.emit(d.shape, Similarity{});
    const auto end = static_cast<uint32_t>(out.shapes.code.size());
    out.terms.push_back({d.h_min, d.slope, d.h_max, begin, end});
  }
  return out;
}

bool nests_indexed_unions(const Program& program) {
  std::vector<uint32_t> open;  // the ends of the indexed unions around the current instruction
  for (uint32_t i = 0; i < program.code.size(); ++i) {
    while (!open.empty() && i >= open.back()) open.pop_back();
    const Instruction& ins = program.code[i];
    if (ins.op != Op::kUnionIndexed || ins.bvh == kNoBvh) continue;
    if (!open.empty()) return true;
    open.push_back(ins.operand);
  }
  return false;
}

}  // namespace meshd
