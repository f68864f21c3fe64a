#include "server/size_grid_conversion.h"

#include <cmath>

#include "core/common/error.h"
#include "server/field_checks.h"
#include "server/grid_conversion.h"

namespace meshd {

GridSize to_grid_size(const v1::GridSize& in, const std::string& path, int64_t limit,
                      int64_t& used) {
  const GridLayout layout = check_grid_layout(in, path, limit, "the size field's grids", used);
  GridSize out;
  out.nx = layout.nx;
  out.ny = layout.ny;
  out.origin = layout.origin;
  out.spacing = layout.spacing;
  out.values.assign(in.values().begin(), in.values().end());
  for (size_t k = 0; k < out.values.size(); ++k) {
    const float v = out.values[k];
    if (std::isfinite(v) && v > 0) continue;
    throw_invalid(at(path, "values", static_cast<int>(k)),
                  "must be finite and > 0" + got(v) + "; it is the sample at column i = " +
                      std::to_string(k % out.nx) + ", row j = " + std::to_string(k / out.nx));
  }
  return out;
}

}  // namespace meshd
