#include "server/distance_grid_conversion.h"

#include <cmath>

#include "core/common/error.h"
#include "server/field_checks.h"
#include "server/grid_conversion.h"

namespace meshd {

DistanceGrid to_distance_grid(const v1::DistanceGrid& in, const std::string& path,
                              int64_t max_samples, int64_t& samples) {
  const GridLayout layout =
      check_grid_layout(in, path, max_samples, "the distance grids of one tree", samples);
  DistanceGrid out;
  out.nx = layout.nx;
  out.ny = layout.ny;
  out.origin = layout.origin;
  out.spacing = layout.spacing;
  bool inside = false;
  for (int k = 0; k < in.values_size(); ++k) {
    const float v = in.values(k);
    if (!std::isfinite(v)) {
      throw_invalid(at(path, "values", k), "must be finite" + got(v) + "; sample (i, j) = (" +
                                               std::to_string(k % out.nx) + ", " +
                                               std::to_string(k / out.nx) + ")");
    }
    inside = inside || v < 0;
  }
  if (!inside) {
    throw_invalid(path + ".values",
                  "has no value < 0: the domain (negative inside) would be empty");
  }
  out.values.assign(in.values().begin(), in.values().end());
  return out;
}

}  // namespace meshd
