// import_polygons for a meshctl built with MESHD_GDAL=OFF: GDAL and its hundred-odd libraries
// are not there, so --import says so instead of reading the file.
#include "client/gis_import.h"
#include "core/common/error.h"

namespace meshd::cli {

ImportedLayer import_polygons(const GisImportOptions&) {
  throw Error(ErrorCode::kFailedPrecondition, "--import",
              "this meshctl was built without GDAL (MESHD_GDAL=OFF); rebuild with it on");
}

}  // namespace meshd::cli
