// Reading a polygon layer of a GIS or CAD file (anything GDAL/OGR opens as vector data: GeoJSON,
// Shapefile, GeoPackage, KML, DXF, ...) as rings in a metric CRS, ready to become CSG shapes.
//
// The order of the steps is fixed, and each names what it works in:
//   1. open the file, pick the layer, apply the attribute filter            (the file's CRS)
//   2. per feature: linearise curves, accept polygons, multipolygons and closed line strings,
//      check validity (GEOS)                                                 (the file's CRS)
//   3. reproject to the output CRS: --to-crs, else the UTM zone of the data's centre when the
//      data is in degrees, else keep the file's coordinates
//   4. clip to the box, 5. simplify (topology preserving)                   (the output CRS)
//   6. rings as vertex lists without the closing vertex; degenerate rings (fewer than 3
//      distinct vertices, no area, or, when simplifying, an area of at most the tolerance
//      squared) are dropped and counted, a polygon with its holes when its outer ring goes.
// Every error is Error(kInvalidArgument) naming the flag it comes from ("--import" for the file
// and its features) and, for a feature, the file, the layer and the feature's FID.
// GDAL stays behind this header: nothing here includes it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/common/vec2.h"

namespace meshd::cli {

struct GisImportOptions {
  std::string path;   // the file (or directory, for data sets that are one)
  std::string layer;  // empty: the first layer
  std::string where;  // OGR SQL attribute filter, e.g. "name = 'Lake'"; empty: every feature
  // Clip box xmin, ymin, xmax, ymax in the output CRS's units; min < max.
  std::optional<std::array<double, 4>> clip;
  // Douglas-Peucker tolerance that keeps topology, in the output CRS's units; 0: none.
  double simplify_tolerance = 0;
  // The data's CRS when the file has none or a wrong one (any text OGRSpatialReference reads:
  // "EPSG:4326", WKT, PROJ); empty: the file's.
  std::string from_crs;
  // The output CRS; empty: the UTM zone of the data's centre for geographic (degree) data, the
  // data's own CRS otherwise; "none": the coordinates as they are, whatever they are.
  std::string to_crs;
};

// One polygon: its outer boundary and its holes, each a ring of #V by 2 vertices in the output
// CRS's units, either orientation, the first vertex not repeated at the end.
struct ImportedPolygon {
  int64_t fid = 0;  // the feature it came from
  std::vector<Vec2> outer;
  std::vector<std::vector<Vec2>> holes;
};

struct ImportedLayer {
  std::string layer;  // the layer's name
  std::string crs;    // the output CRS, e.g. "EPSG:32632 (WGS 84 / UTM zone 32N)"
  std::vector<ImportedPolygon> polygons;
  int features = 0;       // features that contributed at least one polygon
  int dropped_rings = 0;  // degenerate rings left out (step 6), holes included
  int64_t vertices() const;
};

// Reads the polygons of one layer as `options` say. Throws Error(kInvalidArgument) when the file
// cannot be opened, the layer does not exist (the message lists the layers), the filter does
// not parse, nothing is left (empty layer, or after the filter, the clip or the simplification),
// a feature is not polygonal or not valid (the message says why and where), or the CRS cannot
// be converted (no CRS while the coordinates look like degrees, or a failed transform).
ImportedLayer import_polygons(const GisImportOptions& options);

// The UTM zone (1..60) whose 6-degree band holds longitude `lon_deg` (wrapped to [-180, 180)).
int utm_zone(double lon_deg);

}  // namespace meshd::cli
