// read_raster_grid for a meshctl built with MESHD_GDAL=OFF: GDAL is not there to read rasters,
// so the flag says so; NumPy .npy grids still work.
#include "client/raster_grid.h"
#include "core/common/error.h"

namespace meshd::cli {

RasterGrid read_raster_grid(const std::string& path, const std::string& flag) {
  throw Error(ErrorCode::kFailedPrecondition, flag,
              "cannot read " + quote_input(path) +
                  ": this meshctl was built without GDAL (MESHD_GDAL=OFF), so it reads only "
                  "NumPy .npy grids; rebuild with it on, or save the grid with numpy.save");
}

}  // namespace meshd::cli
