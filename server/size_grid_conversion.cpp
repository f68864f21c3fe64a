#include "server/size_grid_conversion.h"

#include <cmath>

#include "core/common/error.h"
#include "server/field_checks.h"

namespace meshd {
namespace {

uint32_t at_least_two(uint32_t n, const std::string& field) {
  if (n < 2) throw_invalid(field, "must be >= 2 (got " + std::to_string(n) + ")");
  return n;
}

}  // namespace

GridSize to_grid_size(const v1::GridSize& in, const std::string& path, int64_t limit,
                      int64_t& used) {
  GridSize out;
  out.nx = at_least_two(in.nx(), path + ".nx");
  out.ny = at_least_two(in.ny(), path + ".ny");
  // Before the count: a request over the limit should learn so, not that its values are short.
  const int64_t count = int64_t{out.nx} * out.ny;
  if (count > limit - used) {
    throw Error(ErrorCode::kResourceExhausted, path + ".values",
                "nx * ny = " + std::to_string(count) + " values; the size field's grids may hold " +
                    std::to_string(limit) + " values together" +
                    (used > 0 ? " (earlier grids hold " + std::to_string(used) + ")" : "") +
                    ": use a coarser grid");
  }
  if (in.values_size() != count) {
    throw_invalid(path + ".values", "must hold nx * ny = " + std::to_string(out.nx) + " * " +
                                        std::to_string(out.ny) + " = " + std::to_string(count) +
                                        " values, row by row (got " +
                                        std::to_string(in.values_size()) + ")");
  }
  if (!in.has_origin()) throw_invalid(path + ".origin", "required: the position of values[0]");
  if (!in.has_spacing()) throw_invalid(path + ".spacing", "required: the samples' spacing");
  out.origin = to_vec2(in.origin(), path + ".origin");
  out.spacing = {positive(in.spacing().x(), path + ".spacing.x"),
                 positive(in.spacing().y(), path + ".spacing.y")};
  const Vec2 far{out.origin.x + (out.nx - 1) * out.spacing.x,
                 out.origin.y + (out.ny - 1) * out.spacing.y};
  if (!(std::isfinite(far.x) && std::isfinite(far.y))) {
    throw_invalid(path + ".spacing",
                  "the grid's far corner, origin + (nx - 1, ny - 1) * spacing, "
                  "must be finite (got (" +
                      num(far.x) + ", " + num(far.y) + "))");
  }
  out.values.assign(in.values().begin(), in.values().end());
  for (int64_t k = 0; k < count; ++k) {
    const float v = out.values[k];
    if (std::isfinite(v) && v > 0) continue;
    throw_invalid(at(path, "values", static_cast<int>(k)),
                  "must be finite and > 0" + got(v) + "; it is the sample at column i = " +
                      std::to_string(k % out.nx) + ", row j = " + std::to_string(k / out.nx));
  }
  used += count;
  return out;
}

}  // namespace meshd
