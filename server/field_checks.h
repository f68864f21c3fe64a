// The pieces of the conversion layer's messages and range checks that more than one converter
// uses: the value as the user wrote it, and the checks that name the field and the allowed range.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

// The value as the user wrote it: the shortest text that reads back as the same double.
std::string num(double v);

// " (got <num(v)>)", the tail of a range message.
std::string got(double v);

// "<path>.<field>[<index>]", the path of a repeated field's entry.
std::string at(const std::string& path, const char* field, int index);

// v, or Error(kInvalidArgument) naming `field` when it is not finite.
double finite(double v, const std::string& field);

// v, or Error(kInvalidArgument) naming `field` unless it is finite and > 0.
double positive(double v, const std::string& field);

// The point, each coordinate checked by finite() as field + ".x" and ".y".
Vec2 to_vec2(const v1::Vec2& v, const std::string& field);

// An estimate or a suggestion: 3 significant digits, whole numbers from 100 up.
std::string approx(double v);

// A size term's h_max: finite and at least its h_min.
double at_least_h_min(double h_max, double h_min, const std::string& field);

// Checks lo < v <= hi (lo_open) or lo <= v <= hi; NaN fails either.
double in_range(double v, double lo, bool lo_open, double hi, const std::string& field);
int in_range(uint32_t v, uint32_t lo, uint32_t hi, const std::string& field);

// What one shape tree (plane or solid) may hold: it counts the nodes a converter enters.
class TreeBudget {
 public:
  TreeBudget(std::string root, int max_depth, int max_nodes)
      : root_(std::move(root)), max_depth_(max_depth), max_nodes_(max_nodes) {}
  const std::string& root() const { return root_; }
  // Enters the node at `path`, `depth` levels down (the root is 1), named `name` (may be
  // empty): Error(kInvalidArgument) naming the path past the depth, the root past the count,
  // or the name's field for a bad name.
  void enter(const std::string& path, int depth, const std::string& name);

 private:
  std::string root_;
  int max_depth_, max_nodes_;
  int nodes_ = 0;
};

}  // namespace meshd
