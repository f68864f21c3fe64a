#include "client/sdf_grid_shape.h"

#include <cmath>

#include "client/npy_file.h"
#include "core/common/error.h"

namespace meshd::cli {

v1::Shape sdf_grid_shape(const std::string& path, std::pair<double, double> origin,
                         std::pair<double, double> spacing, const std::string& name) {
  const std::string flag = "--sdf-grid";
  const NpyArray a = read_npy(path, flag);
  auto fail = [&](const std::string& why) { throw_invalid(flag, "'" + path + "': " + why); };
  if (a.shape.size() != 2 || a.shape[0] < 2 || a.shape[1] < 2) {
    std::string shape;
    for (const int64_t d : a.shape) shape += (shape.empty() ? "" : ", ") + std::to_string(d);
    fail("an array of shape (" + shape +
         "); a distance grid is 2-D, [rows, columns] with at "
         "least 2 of each");
  }
  const int64_t ny = a.shape[0], nx = a.shape[1];
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
  g->set_ny(static_cast<uint32_t>(ny));
  g->mutable_origin()->set_x(origin.first);
  g->mutable_origin()->set_y(origin.second);
  g->set_dx(spacing.first);
  g->set_dy(spacing.second);
  g->mutable_values()->Assign(a.values.begin(), a.values.end());
  return shape;
}

}  // namespace meshd::cli
