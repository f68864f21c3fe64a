// The geometry as a tree, in plain C++: what a request describes after validation.
//
// Distances are signed, negative inside. Operations follow the usual CSG algebra on signed
// distance functions: union = min, intersection = max, difference a \ b = max(a, -b). Transforms
// are similarities (rotation, uniform scale, translation), so the compiler folds them into the
// primitives and every primitive distance stays exact.
//
// Each node keeps `path`, the request field it came from, so that errors found later (while
// compiling, or detecting corners) can still name the field.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/common/vec2.h"

namespace meshd {

struct Circle {
  Vec2 center;
  double radius = 0.0;  // > 0
};

// Axis-aligned before any enclosing transform.
struct Rectangle {
  Vec2 min;
  Vec2 max;  // max.x > min.x, max.y > min.y
};

// A simple polygon, either orientation; #V by 2 with V >= 3, not closed (last != first).
struct Polygon {
  std::vector<Vec2> vertices;
};

// Axis-aligned before any enclosing transform.
struct Ellipse {
  Vec2 center;
  double semi_axis_x = 0.0;  // > 0
  double semi_axis_y = 0.0;  // > 0
};

// The closed half-plane dot(normal, p) <= offset. normal need not be unit length.
struct HalfPlane {
  Vec2 normal;
  double offset = 0.0;
};

// A signed distance sampled on a regular grid (DistMesh's dmatrix): values[j * nx + i] at
// origin + (i * spacing.x, j * spacing.y), negative inside. The domain is where the bilinear
// interpolant is negative, within the grid's box; its distance is as exact as the data.
struct DistanceGrid {
  Vec2 origin;
  Vec2 spacing;               // > 0
  uint32_t nx = 0, ny = 0;    // >= 2
  std::vector<float> values;  // nx * ny, finite, row by row
};

enum class CsgOp { kUnion, kIntersection, kDifference };

struct Shape;

// Union and intersection take one or more operands; difference is operands[0] minus the rest.
struct Csg {
  CsgOp op = CsgOp::kUnion;
  std::vector<Shape> operands;
};

// p -> scale * R(angle) * p + offset: rotate about the origin, then scale, then translate.
struct Similarity {
  double scale = 1.0;  // > 0
  double angle = 0.0;  // radians, counter-clockwise
  Vec2 offset;
};

Similarity compose(const Similarity& outer, const Similarity& inner);
Vec2 apply(const Similarity& t, Vec2 p);

// The operand is stored in a one-element vector so that Shape can stay a value type.
struct Transformed {
  Similarity transform;
  std::vector<Shape> operand;  // exactly one
};

struct Shape {
  std::variant<Circle, Rectangle, Polygon, Ellipse, HalfPlane, DistanceGrid, Csg, Transformed> node;
  std::string name;  // boundary group name for the primitives below; may be empty
  std::string path;  // request field path, for errors
};

// Depth of the tree: a primitive has depth 1.
int tree_depth(const Shape& shape);
// Number of nodes in the tree.
int tree_size(const Shape& shape);

}  // namespace meshd
