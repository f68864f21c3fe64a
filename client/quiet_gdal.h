// GDAL for meshctl's readers (gis_import.cpp, raster_grid.cpp): its drivers registered once, and
// its errors and warnings kept off stderr while a file is read, to be quoted in meshctl's own
// messages instead. Included only where GDAL is linked (MESHD_GDAL).
#pragma once

#include <cpl_error.h>
#include <gdal_priv.h>

#include <mutex>
#include <string>

namespace meshd::cli {

// While alive, GDAL's errors and warnings are not printed; last_message() gives the latest.
// The first one registers GDAL's drivers.
class QuietGdal {
 public:
  QuietGdal() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;

  static std::string last_message() {
    const char* m = CPLGetLastErrorMsg();
    return m != nullptr ? m : "";
  }
};

}  // namespace meshd::cli
