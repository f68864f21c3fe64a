// The gridded size term meshctl adds to a request: --size-grid FILE, a NumPy .npy array indexed
// [j, i] (npy_file.h) or, in a meshctl built with GDAL, a GeoTIFF or any raster GDAL reads
// (raster_grid.h), with --size-grid-origin and --size-grid-spacing (required for .npy, where the
// file holds no coordinates; for a raster they replace its geotransform's).
#pragma once

#include <optional>
#include <string>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd::cli {

struct SizeGridOptions {
  std::string path;             // empty: no grid
  std::optional<Vec2> origin;   // the position of sample [0, 0]
  std::optional<Vec2> spacing;  // > 0 both
};

// The grid term of `options.path`. Throws Error(kInvalidArgument) naming the flag and the file:
// a .npy that is not 2-D or smaller than 2 x 2, missing origin or spacing, a value that is not
// finite and > 0 (by its index); Error(kFailedPrecondition) for a raster without GDAL.
v1::GridSize read_size_grid(const SizeGridOptions& options);

}  // namespace meshd::cli
