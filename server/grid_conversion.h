// The layout that every gridded input of a request shares (geometry.proto's DistanceGrid and
// GridSize): the one place that decides what a regular grid of samples may be. What the values
// themselves may be is each kind's own check.
#pragma once

#include <cstdint>
#include <string>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

struct GridLayout {
  uint32_t nx = 0, ny = 0;  // >= 2
  Vec2 origin;              // finite; (0, 0) when absent
  Vec2 spacing;             // finite, > 0 in both coordinates
};

// The layout of the grid at request field `path`. `used` counts the samples of the grids checked
// so far that share `limit` (`scope` names them in the message, e.g. "the grids of this tree");
// this grid's nx * ny are added, counted before its values are read. Throws
// Error(kResourceExhausted) naming path + ".values" above the limit, else
// Error(kInvalidArgument) naming the field: nx or ny < 2, a values count other than nx * ny, no
// spacing or one not finite and > 0, an origin or a far corner that is not finite.
GridLayout check_grid_layout(uint32_t nx, uint32_t ny, const v1::Vec2* origin,
                             const v1::Vec2* spacing, int64_t values, const std::string& path,
                             int64_t limit, const std::string& scope, int64_t& used);

template <class GridProto>
GridLayout check_grid_layout(const GridProto& in, const std::string& path, int64_t limit,
                             const std::string& scope, int64_t& used) {
  return check_grid_layout(in.nx(), in.ny(), in.has_origin() ? &in.origin() : nullptr,
                           in.has_spacing() ? &in.spacing() : nullptr, in.values_size(), path,
                           limit, scope, used);
}

}  // namespace meshd
