#include "server/distance_grid_conversion.h"

#include <algorithm>
#include <cmath>

#include "core/common/error.h"
#include "server/field_values.h"

namespace meshd {

DistanceGrid to_distance_grid(const v1::DistanceGrid& in, const std::string& path,
                              int64_t max_samples, int64_t& samples) {
  for (const auto& [n, field] : {std::pair{in.nx(), ".nx"}, std::pair{in.ny(), ".ny"}}) {
    if (n < 2) {
      throw_invalid(path + field,
                    "must be >= 2 (samples along that axis; got " + std::to_string(n) + ")");
    }
  }
  // The limit first: a grid too large is refused before its values are read.
  const int64_t expected = int64_t{in.nx()} * in.ny();
  const int64_t count = in.values_size();
  samples += std::max(expected, count);
  if (samples > max_samples) {
    throw Error(ErrorCode::kResourceExhausted, path + ".values",
                "the grids of this tree hold " + std::to_string(samples) +
                    " samples, more than the server's limit of " + std::to_string(max_samples) +
                    ": resample the grid more coarsely");
  }
  if (count != expected) {
    throw_invalid(path + ".values", "must hold nx * ny = " + std::to_string(in.nx()) + " * " +
                                        std::to_string(in.ny()) + " = " + std::to_string(expected) +
                                        " values, row by row (got " + std::to_string(count) + ")");
  }
  DistanceGrid out;
  out.nx = in.nx();
  out.ny = in.ny();
  out.spacing = {positive(in.dx(), path + ".dx"), positive(in.dy(), path + ".dy")};
  out.origin = to_vec2(in.origin(), path + ".origin");
  // The far corner must be finite too: a huge spacing times many samples overflows.
  const Vec2 far{out.origin.x + (out.nx - 1) * out.spacing.x,
                 out.origin.y + (out.ny - 1) * out.spacing.y};
  if (!std::isfinite(far.x) || !std::isfinite(far.y)) {
    throw_invalid(path, "the grid's far corner origin + ((nx-1) dx, (ny-1) dy) = (" + num(far.x) +
                            ", " + num(far.y) + ") must be finite");
  }
  bool inside = false;
  for (int k = 0; k < count; ++k) {
    const float v = in.values(k);
    if (!std::isfinite(v)) {
      throw_invalid(path + ".values[" + std::to_string(k) + "]",
                    "must be finite" + got(v) + "; sample (i, j) = (" + std::to_string(k % out.nx) +
                        ", " + std::to_string(k / out.nx) + ")");
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
