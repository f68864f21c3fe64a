// The 3D benchmark domains (issue 16's examples), by name, until 3D requests have a file format.
#pragma once

#include <string>

#include "core/geometry3d/shape3d.h"
#include "core/geometry3d/size_field3.h"

namespace meshd::bench {

struct Case3 {
  Shape3 shape;
  double h0 = 0.1;  // the domain's default edge length
  SizeField3 size;  // relative size field, its smallest value 1; no terms: uniform
};

// The domain called `name`; throws Error(kInvalidArgument) naming the known ones otherwise.
Case3 case3d(const std::string& name);
// The known names, comma-separated.
std::string case3d_names();

}  // namespace meshd::bench
