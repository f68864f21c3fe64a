#include "server/grid_conversion.h"

#include <cmath>

#include "core/common/error.h"
#include "server/field_checks.h"

namespace meshd {

GridLayout check_grid_layout(uint32_t nx, uint32_t ny, const v1::Vec2* origin,
                             const v1::Vec2* spacing, int64_t values, const std::string& path,
                             int64_t limit, const std::string& scope, int64_t& used) {
  GridLayout out;
  for (const auto& [n, field] : {std::pair{nx, ".nx"}, std::pair{ny, ".ny"}}) {
    if (n < 2) {
      throw_invalid(path + field,
                    "must be >= 2 (samples along that axis; got " + std::to_string(n) + ")");
    }
  }
  out.nx = nx;
  out.ny = ny;
  // Before the count: a request over the limit should learn so, not that its values are short,
  // and a header that claims 10^10 samples is refused before anything is read for it.
  const int64_t count = int64_t{nx} * ny;
  if (count > limit - used) {
    throw Error(ErrorCode::kResourceExhausted, path + ".values",
                "nx * ny = " + std::to_string(count) + " samples; " + scope + " may hold " +
                    std::to_string(limit) + " together" +
                    (used > 0 ? " (earlier ones hold " + std::to_string(used) + ")" : "") +
                    ": resample the grid more coarsely");
  }
  if (values != count) {
    throw_invalid(path + ".values", "must hold nx * ny = " + std::to_string(nx) + " * " +
                                        std::to_string(ny) + " = " + std::to_string(count) +
                                        " values, row by row (got " + std::to_string(values) +
                                        ")");
  }
  if (spacing == nullptr) throw_invalid(path + ".spacing", "required: the samples' spacing");
  if (origin != nullptr) out.origin = to_vec2(*origin, path + ".origin");
  out.spacing = {positive(spacing->x(), path + ".spacing.x"),
                 positive(spacing->y(), path + ".spacing.y")};
  // A huge spacing times many samples overflows.
  const Vec2 far{out.origin.x + (nx - 1) * out.spacing.x, out.origin.y + (ny - 1) * out.spacing.y};
  if (!(std::isfinite(far.x) && std::isfinite(far.y))) {
    throw_invalid(path + ".spacing",
                  "the grid's far corner, origin + (nx - 1, ny - 1) * spacing, must be finite "
                  "(got (" + num(far.x) + ", " + num(far.y) + "))");
  }
  used += count;
  return out;
}

}  // namespace meshd
