// meshctl --sdf-grid: a signed-distance grid from a NumPy .npy file as a DistanceGrid shape.
#pragma once

#include <string>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd::cli {

// The 2-D array in `path` (indexed [j, i], row j at y = origin.y + j * dy: npy_file.h) as a
// DistanceGrid named `name`, origin and spacing (dx, dy) in the request's length unit. Throws
// Error(kInvalidArgument) naming --sdf-grid and the file when the array is not 2-D with at least
// 2 x 2 values, or holds a value that is not finite in single precision (its [j, i] said); the
// server checks the rest (geometry.proto).
v1::Shape sdf_grid_shape(const std::string& path, Vec2 origin, Vec2 spacing,
                         const std::string& name);

}  // namespace meshd::cli
