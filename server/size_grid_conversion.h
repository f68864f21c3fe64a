// Validation and conversion of a size field's grid term (meshd.v1.GridSize), beside the rest of
// the size field in request_conversion.cpp.
#pragma once

#include <cstdint>
#include <string>

#include "core/geometry/size_field.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

// The grid term `in`, checked against the ranges its proto comment states.
//   path   its field path, e.g. "size.terms[2].grid"
//   limit  the values that all grids of the request may hold together
//   used   the values earlier grids of the request hold; this grid's are added
// Throws Error(kInvalidArgument) naming the field (the first bad value by its index and its
// column and row), or Error(kResourceExhausted) naming path + ".values" when nx * ny would take
// the request's grids past `limit`.
GridSize to_grid_size(const v1::GridSize& in, const std::string& path, int64_t limit,
                      int64_t& used);

}  // namespace meshd
