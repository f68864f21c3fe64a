// Validation and conversion of a DistanceGrid shape (geometry.proto): the one place that decides
// what a sampled signed-distance grid may be.
#pragma once

#include <cstdint>
#include <string>

#include "core/geometry/shape.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

// The grid at request field `path` (ending in ".distance_grid"). Throws Error(kInvalidArgument)
// naming the field: nx or ny < 2, a values count other than nx * ny, dx or dy not finite and
// > 0, origin not finite, values[k] not finite (the first such k), or no value < 0 (the domain
// would be empty). `samples` counts the grid samples of the tree so far; when this grid would
// take it above `max_samples`, throws Error(kResourceExhausted) naming path + ".values".
DistanceGrid to_distance_grid(const v1::DistanceGrid& in, const std::string& path,
                              int64_t max_samples, int64_t& samples);

}  // namespace meshd
