#include "client/sdf_grid_shape.h"

#include <cmath>

#include "client/npy_file.h"
#include "core/common/error.h"

namespace meshd::cli {

v1::Shape sdf_grid_shape(const std::string& path, Vec2 origin, Vec2 spacing,
                         const std::string& name) {
  const std::string flag = "--sdf-grid";
  const NpyGrid a = read_npy_grid(path, flag, "a distance grid");
  auto fail = [&](const std::string& why) { throw_invalid(flag, "'" + path + "': " + why); };
  const int64_t nx = a.nx;
  for (size_t k = 0; k < a.values.size(); ++k) {
    if (std::isfinite(a.values[k])) continue;
    fail("the value at [" + std::to_string(int64_t(k) / nx) + ", " +
         std::to_string(int64_t(k) % nx) + "] is " + std::to_string(a.values[k]) +
         " in single precision; every value must be finite");
  }
  v1::Shape shape;
  shape.set_name(name);
  auto* g = shape.mutable_distance_grid();
  g->set_nx(static_cast<uint32_t>(nx));
  g->set_ny(a.ny);
  g->mutable_origin()->set_x(origin.x);
  g->mutable_origin()->set_y(origin.y);
  g->mutable_spacing()->set_x(spacing.x);
  g->mutable_spacing()->set_y(spacing.y);
  g->mutable_values()->Assign(a.values.begin(), a.values.end());
  return shape;
}

}  // namespace meshd::cli
