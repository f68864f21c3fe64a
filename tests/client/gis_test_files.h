// Small GIS files for the import tests, written by the tests themselves: GeoJSON as text, other
// formats through GDAL's own writers.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/common/vec2.h"

namespace meshd::testing {

// A fresh directory under the system's temporary directory, removed with its contents.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

// "[[x,y],...,[x0,y0]]": a GeoJSON ring of `ring` (#V by 2), closed by repeating the first.
std::string geojson_ring(const std::vector<Vec2>& ring);

// One feature: "id" fid, property name, and `geometry` (GeoJSON text).
std::string geojson_feature(int fid, const std::string& name, const std::string& geometry);

// A FeatureCollection named `layer` of `features` (geojson_feature texts). `epsg` > 0 adds a
// "crs" member; 0 leaves it out (GeoJSON's default: WGS 84 longitude/latitude).
std::string geojson(const std::string& layer, const std::vector<std::string>& features,
                    int epsg = 0);

// Writes `text` to `path` and returns `path`.
std::string write_text(const std::string& path, const std::string& text);

// One layer to write with GDAL: its name, its CRS (EPSG code; 0: none) and its features as WKT
// with a "name" attribute.
struct TestLayer {
  std::string name;
  int epsg = 0;
  std::vector<std::pair<std::string, std::string>> features;  // (WKT, name)
};

// Writes `layers` into a new data set at `path` with the GDAL driver `driver` ("GPKG", "ESRI
// Shapefile", "DXF", ...); returns `path`. Fails the calling test (ADD_FAILURE) when GDAL cannot.
std::string write_with_gdal(const std::string& path, const std::string& driver,
                            const std::vector<TestLayer>& layers);

// An axis-aligned square ring, counter-clockwise from (x0, y0).
std::vector<Vec2> square(double x0, double y0, double side);

// A regular n-gon of radius r about c, counter-clockwise.
std::vector<Vec2> circle(Vec2 c, double r, int n);

// The signed (counter-clockwise positive) area of a ring.
double ring_area(const std::vector<Vec2>& ring);

}  // namespace meshd::testing
