// The geometry compiled to a flat postfix program, so that one small evaluator (sdf_eval.cuh)
// computes the signed distance on the host and on the device alike.
//
// Invariants: `code` is postfix over a value stack. A primitive instruction pushes its distance;
// kMin and kMax pop two values and push one; kNegate flips the top. A well-formed program
// leaves exactly one value and never needs more than kMaxProgramStack slots (the compiler
// checks both). Transforms are similarities, so the compiler has already folded them into the
// primitives' parameters: every analytic primitive distance is exact (a sampled grid's is as exact
// as its data), and evaluation needs no matrices.
//
// Spatial indexes (bvh.h) make large geometries cost about what small ones do, without
// changing a single distance:
//   - a polygon of many vertices carries a tree over runs of its edges (Instruction::bvh);
//   - a union of many operands (and the subtrahends of a difference of many) is preceded by a
//     kUnionIndexed instruction whose tree has one leaf per operand, covering that operand's
//     instructions (kNoBvh where an operand needs more than kMaxIndexedOperandStack slots).
//     The ordinary left fold of the operands follows it, so a reader that skips
//     kUnionIndexed (the bounds, the corner search, a nested evaluation) still sees the whole
//     union; the evaluator instead visits the operands near the point and jumps to `operand`,
//     the instruction after the fold.
//
// Gridded data (regular_grid.h) keeps its header in `params` and its values in `samples`.
//
// Parameter layout in `params`, starting at Instruction::operand:
//   kCircle     cx cy r
//   kBox        cx cy hx hy cos sin          (half extents in the box's own rotated frame)
//   kEllipse    cx cy a b cos sin            (semi axes in the ellipse's own rotated frame)
//   kHalfPlane  nx ny c                      (unit normal; inside where n.p <= c)
//   kPolygon    n x0 y0 x1 y1 ... x(n-1) y(n-1) s   (s = +1 counter-clockwise, -1 clockwise)
//   kGrid       <grid header, kGridParams> tx ty cos sin scale
//               (the grid in its own frame, and the similarity that places it: world p maps to
//               R(-angle) (p - t) / scale in the grid's frame, where the distance is scale
//               times the grid's; grid_sdf.cuh)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/bvh.h"

namespace meshd {

constexpr int kMaxProgramStack = 40;
// The stack of one operand of an indexed union: small, so that the nested evaluations cost the
// device little local memory. A union with a deeper operand keeps kUnionIndexed without a tree
// (bvh == kNoBvh), and its fold runs.
constexpr int kMaxIndexedOperandStack = 8;

enum class Op : uint32_t {
  kCircle,
  kBox,
  kEllipse,
  kHalfPlane,
  kPolygon,
  kGrid,
  kMin,
  kMax,
  kNegate,
  kUnionIndexed
};

constexpr uint32_t kNoBvh = 0xffffffffu;

struct Instruction {
  Op op;
  uint32_t operand;       // primitives: offset into params; kUnionIndexed: the end of its fold
  int32_t primitive;      // index into Program::primitives; -1 for operations
  uint32_t bvh = kNoBvh;  // root in Program::nodes: a kPolygon's edges, a kUnionIndexed's operands
};

// What the host needs to know about each primitive beyond its distance.
struct PrimitiveInfo {
  std::string name;             // boundary group name
  std::string path;             // request field path, for errors
  std::vector<double> corners;  // #C by 2 (flattened): polygon, rectangle and grid-box corners,
                                // transformed
};

// Trivially copyable view of a program, passed by value to device code.
struct ProgramView {
  const Instruction* code;
  uint32_t size;
  const double* params;
  const BvhNode* nodes;
  const float* samples;
};

struct Program {
  std::vector<Instruction> code;
  std::vector<double> params;
  std::vector<BvhNode> nodes;
  std::vector<float> samples;  // gridded data, regular_grid.h
  std::vector<PrimitiveInfo> primitives;

  ProgramView view() const {
    return {code.data(), static_cast<uint32_t>(code.size()), params.data(), nodes.data(),
            samples.data()};
  }
};

}  // namespace meshd
