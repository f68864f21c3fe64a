#include "client/raster_grid.h"

#include <cpl_error.h>
#include <gdal_priv.h>

#include <cmath>
#include <filesystem>

#include "client/quiet_gdal.h"
#include "core/common/error.h"

namespace meshd::cli {
namespace {

// GDAL's latest message as the tail of one of ours: ": <message>", or nothing.
std::string gdal_says() {
  const std::string m = QuietGdal::last_message();
  return m.empty() ? "" : ": " + m;
}

// A grid larger than this is beyond any server's default limit of grid values; refusing it
// here saves reading gigabytes only to be told so.
constexpr double kMaxPixels = 1e9;

}  // namespace

RasterGrid read_raster_grid(const std::string& path, const std::string& flag) {
  const QuietGdal quiet;
  const std::string file = quote_input(path);
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored))
    throw_invalid(flag, "cannot open " + file + ": no such file or directory");
  const GDALDatasetUniquePtr data(
      GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!data) {
    throw_invalid(flag, "cannot open " + file + " as raster data" +
                            (gdal_says().empty() ? " (no GDAL driver recognises it)" : gdal_says()));
  }
  if (data->GetRasterCount() < 1) throw_invalid(flag, file + " has no raster band");
  const int width = data->GetRasterXSize(), height = data->GetRasterYSize();
  if (width < 2 || height < 2) {
    throw_invalid(flag, file + " is " + std::to_string(width) + " x " + std::to_string(height) +
                            " pixels; a size grid needs at least 2 x 2");
  }
  if (double(width) * height > kMaxPixels)
    throw_invalid(flag, file + " has more than 1e9 pixels; resample it coarser");

  RasterGrid out;
  out.nx = static_cast<uint32_t>(width);
  out.ny = static_cast<uint32_t>(height);
  double gt[6];
  // Rows run down the file when gt[5] < 0 (north-up, the usual case): they are flipped below.
  bool rows_down = true;
  if (data->GetGeoTransform(gt) == CE_None) {
    if (gt[2] != 0 || gt[4] != 0) {
      throw_invalid(flag, file + " is rotated or sheared (geotransform terms " +
                              std::to_string(gt[2]) + ", " + std::to_string(gt[4]) +
                              "); only north-up rasters are read: warp it north-up first "
                              "(gdalwarp)");
    }
    if (!(gt[1] > 0 && gt[5] != 0 && std::isfinite(gt[1]) && std::isfinite(gt[5]) &&
          std::isfinite(gt[0]) && std::isfinite(gt[3]))) {
      throw_invalid(flag, file +
                              " has a geotransform without a positive pixel width or with a "
                              "zero pixel height");
    }
    rows_down = gt[5] < 0;
    out.spacing = Vec2{gt[1], std::fabs(gt[5])};
    // The centre of the bottom row's first pixel.
    out.origin = Vec2{gt[0] + 0.5 * gt[1], gt[3] + (rows_down ? height - 0.5 : 0.5) * gt[5]};
  }

  GDALRasterBand* band = data->GetRasterBand(1);
  std::vector<float> file_rows(static_cast<size_t>(width) * height);
  if (band->RasterIO(GF_Read, 0, 0, width, height, file_rows.data(), width, height, GDT_Float32, 0,
                     0) != CE_None) {
    throw_invalid(flag, "cannot read the pixels of " + file + gdal_says());
  }
  int has_no_data = 0;
  const double no_data = band->GetNoDataValue(&has_no_data);
  out.values.resize(file_rows.size());
  for (int r = 0; r < height; ++r) {
    const int j = rows_down ? height - 1 - r : r;
    for (int i = 0; i < width; ++i) {
      const float v = file_rows[static_cast<size_t>(r) * width + i];
      if (!std::isfinite(v) || (has_no_data && v == static_cast<float>(no_data))) {
        throw_invalid(flag, file + ": the pixel at column " + std::to_string(i) + ", row " +
                                std::to_string(r) + " (from the top) has no data (" +
                                std::to_string(v) +
                                "); a size grid needs a value everywhere: fill the gaps first");
      }
      out.values[static_cast<size_t>(j) * width + i] = v;
    }
  }
  return out;
}

}  // namespace meshd::cli
