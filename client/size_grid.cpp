#include "client/size_grid.h"

#include <cctype>
#include <cmath>
#include <limits>

#include "client/npy_file.h"
#include "client/raster_grid.h"
#include "core/common/error.h"

namespace meshd::cli {
namespace {

constexpr const char* kFlag = "--size-grid";

bool is_npy(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == ".npy";
}

}  // namespace

v1::GridSize read_size_grid(const SizeGridOptions& o) {
  const std::string file = quote_input(o.path);
  uint32_t nx = 0, ny = 0;
  std::vector<float> values;
  std::optional<Vec2> origin = o.origin, spacing = o.spacing;
  if (is_npy(o.path)) {
    NpyGrid a = read_npy_grid(o.path, kFlag, "a size grid");
    if (!origin) throw_invalid("--size-grid-origin", "required with a .npy grid: x,y of [0, 0]");
    if (!spacing) throw_invalid("--size-grid-spacing", "required with a .npy grid: d or dx,dy");
    nx = a.nx;
    ny = a.ny;
    values = std::move(a.values);
  } else {
    RasterGrid r = read_raster_grid(o.path, kFlag);
    if (!origin) origin = r.origin;
    if (!spacing) spacing = r.spacing;
    if (!origin || !spacing) {
      throw_invalid(kFlag, file +
                               " has no geotransform: give --size-grid-origin and "
                               "--size-grid-spacing");
    }
    nx = r.nx;
    ny = r.ny;
    values = std::move(r.values);
  }
  // The server checks these too; here the message can name the file and the array's index.
  for (size_t k = 0; k < values.size(); ++k) {
    if (std::isfinite(values[k]) && values[k] > 0) continue;
    throw_invalid(kFlag, file + ": the value at [" + std::to_string(k / nx) + ", " +
                             std::to_string(k % nx) + "] (row j, column i) is " +
                             std::to_string(values[k]) +
                             "; a size grid's values must be finite "
                             "and > 0");
  }
  v1::GridSize out;
  out.set_nx(nx);
  out.set_ny(ny);
  out.mutable_origin()->set_x(origin->x);
  out.mutable_origin()->set_y(origin->y);
  out.mutable_spacing()->set_x(spacing->x);
  out.mutable_spacing()->set_y(spacing->y);
  out.mutable_values()->Assign(values.begin(), values.end());
  return out;
}

}  // namespace meshd::cli
