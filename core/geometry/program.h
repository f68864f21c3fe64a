// The geometry compiled to a flat postfix program, so that one small evaluator (sdf_eval.cuh)
// computes the signed distance on the host and on the device alike.
//
// Invariants: `code` is postfix over a value stack. A primitive instruction pushes its distance;
// kMin and kMax pop two values and push one; kNegate flips the top. A well-formed program
// leaves exactly one value and never needs more than kMaxProgramStack slots (the compiler
// checks both). Transforms are similarities, so the compiler has already folded them into the
// primitives' parameters: every primitive distance is exact, and evaluation needs no matrices.
//
// Parameter layout in `params`, starting at Instruction::operand:
//   kCircle     cx cy r
//   kBox        cx cy hx hy cos sin          (half extents in the box's own rotated frame)
//   kEllipse    cx cy a b cos sin            (semi axes in the ellipse's own rotated frame)
//   kHalfPlane  nx ny c                      (unit normal; inside where n.p <= c)
//   kPolygon    n x0 y0 x1 y1 ... x(n-1) y(n-1)
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshd {

constexpr int kMaxProgramStack = 40;

enum class Op : uint32_t { kCircle, kBox, kEllipse, kHalfPlane, kPolygon, kMin, kMax, kNegate };

struct Instruction {
  Op op;
  uint32_t operand;   // offset into params (primitives only)
  int32_t primitive;  // index into Program::primitives; -1 for operations
};

// What the host needs to know about each primitive beyond its distance.
struct PrimitiveInfo {
  std::string name;             // boundary group name
  std::string path;             // request field path, for errors
  std::vector<double> corners;  // #C by 2 (flattened): polygon and rectangle corners, transformed
};

// Trivially copyable view of a program, passed by value to device code.
struct ProgramView {
  const Instruction* code;
  uint32_t size;
  const double* params;
};

struct Program {
  std::vector<Instruction> code;
  std::vector<double> params;
  std::vector<PrimitiveInfo> primitives;

  ProgramView view() const {
    return {code.data(), static_cast<uint32_t>(code.size()), params.data()};
  }
};

}  // namespace meshd
