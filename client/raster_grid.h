// Reading one band of a raster file (a GeoTIFF, or anything GDAL opens as raster data) as a
// regular grid of samples: a gridded size field from GIS tools.
//
// A pixel's value is the sample at the pixel's centre. The geotransform must be north-up (no
// rotation or shear terms); its rows, which GDAL lists top down, are flipped so that row j lies
// at y = origin.y + j * spacing.y, counted upwards, as everywhere else in meshd. Without a
// geotransform, origin and spacing come back unset (the caller must give them).
// Every error is Error(kInvalidArgument) naming `flag` and the file.
// GDAL stays behind this header: nothing here includes it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/common/vec2.h"

namespace meshd::cli {

struct RasterGrid {
  std::optional<Vec2> origin;   // centre of the lower-left pixel
  std::optional<Vec2> spacing;  // > 0 both
  uint32_t nx = 0, ny = 0;      // columns, rows
  std::vector<float> values;    // nx * ny, row by row from the bottom row up
};

// Band 1 of `path`. Pixels equal to the band's no-data value, and values that are not finite,
// are errors that name their column and row (counted from the top, as GIS tools show them).
RasterGrid read_raster_grid(const std::string& path, const std::string& flag);

}  // namespace meshd::cli
