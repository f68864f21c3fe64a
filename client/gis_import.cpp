#include "client/gis_import.h"

#include <cpl_error.h>
#include <gdal_priv.h>
#include <geos_c.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "client/quiet_gdal.h"
#include "core/common/error.h"

namespace meshd::cli {

namespace {

constexpr const char* kField = "--import";

struct CtDeleter {
  void operator()(OGRCoordinateTransformation* ct) const {
    OGRCoordinateTransformation::DestroyCT(ct);
  }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, CtDeleter>;
using MultiPolygonPtr = std::unique_ptr<OGRMultiPolygon>;

// ---------------------------------------------------------------------------------------------
// Geometry helpers.

// GEOS's reason for an invalid geometry, e.g. "Self-intersection[10 5]".
std::string invalid_reason(const OGRGeometry& g) {
  GEOSContextHandle_t context = OGRGeometry::createGEOSContext();
  std::string reason = "not a valid polygon";
  if (GEOSGeom geos = g.exportToGEOS(context)) {
    if (char* text = GEOSisValidReason_r(context, geos)) {
      reason = text;
      GEOSFree_r(context, text);
    }
    GEOSGeom_destroy_r(context, geos);
  }
  OGRGeometry::freeGEOSContext(context);
  return reason;
}

// Adds the polygons in `g` to `out` (collections are opened); returns false when `g` holds
// anything else. Closed line strings count as polygons without holes: DXF and KML store
// outlines so.
bool add_polygons(const OGRGeometry& g, OGRMultiPolygon& out) {
  switch (wkbFlatten(g.getGeometryType())) {
    case wkbPolygon:
      out.addGeometry(&g);
      return true;
    case wkbLineString:
    case wkbLinearRing: {
      const auto& line = *g.toLineString();
      if (line.getNumPoints() < 4 || !line.get_IsClosed()) return false;
      OGRLinearRing ring;
      ring.addSubLineString(&line);
      OGRPolygon polygon;
      polygon.addRing(&ring);
      out.addGeometry(&polygon);
      return true;
    }
    case wkbMultiPolygon:
    case wkbMultiLineString:
    case wkbGeometryCollection:
      for (const OGRGeometry* part : *g.toGeometryCollection()) {
        if (!add_polygons(*part, out)) return false;
      }
      return true;
    default:
      return false;
  }
}

// The polygonal parts of `g` only: what an intersection leaves may include the points and
// lines where a polygon touches the clip box, and an empty intersection is an empty polygon.
void keep_polygons(const OGRGeometry& g, OGRMultiPolygon& out) {
  const auto type = wkbFlatten(g.getGeometryType());
  if (g.IsEmpty()) return;
  if (type == wkbPolygon) {
    out.addGeometry(&g);
  } else if (type == wkbMultiPolygon || type == wkbGeometryCollection) {
    for (const OGRGeometry* part : *g.toGeometryCollection()) keep_polygons(*part, out);
  }
}

// The ring without its closing vertex and without repeated consecutive vertices; empty when it
// is degenerate: fewer than 3 distinct vertices, no area against its size, or an area of at most
// min_area (the square of the simplification tolerance: topology-preserving simplification
// never collapses a ring, but one that fits in a tolerance-wide square is below the resolution
// that was asked for).
std::vector<Vec2> ring_vertices(const OGRLinearRing& ring, double min_area) {
  std::vector<Vec2> v;
  v.reserve(static_cast<size_t>(ring.getNumPoints()));
  for (int i = 0; i < ring.getNumPoints(); ++i) {
    const Vec2 p{ring.getX(i), ring.getY(i)};
    if (v.empty() || !(p == v.back())) v.push_back(p);
  }
  while (v.size() > 1 && v.back() == v.front()) v.pop_back();
  if (v.size() < 3) return {};
  // Shoelace about the first vertex, so that large coordinates (UTM northings) do not cancel.
  double twice_area = 0;
  Box box{v[0], v[0]};
  for (size_t i = 1; i + 1 < v.size(); ++i) twice_area += cross(v[i] - v[0], v[i + 1] - v[0]);
  for (const Vec2 p : v) {
    box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y)};
    box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y)};
  }
  const double span = std::max(box.max.x - box.min.x, box.max.y - box.min.y);
  if (!(std::abs(twice_area) > std::max(1e-12 * span * span, 2 * min_area))) return {};
  return v;
}

// ---------------------------------------------------------------------------------------------
// The coordinate systems.

std::string describe(const OGRSpatialReference& srs) {
  std::string text;
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority != nullptr && code != nullptr) text = std::string(authority) + ":" + code;
  const char* name = srs.GetName();
  if (name != nullptr && *name != '\0')
    text += text.empty() ? name : " (" + std::string(name) + ")";
  return text.empty() ? "an unnamed CRS" : text;
}

std::unique_ptr<OGRSpatialReference> crs_from_text(const std::string& text,
                                                   const std::string& flag) {
  auto srs = std::make_unique<OGRSpatialReference>();
  CPLErrorReset();
  if (srs->SetFromUserInput(text.c_str()) != OGRERR_NONE) {
    const std::string why = QuietGdal::last_message();
    throw_invalid(flag, "not a coordinate reference system: " + quote_input(text) +
                            (why.empty() ? "" : " (" + why + ")") +
                            "; give e.g. EPSG:32632, a WKT or a PROJ string");
  }
  srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = easting or longitude
  return srs;
}

// The UTM zone of the data's centre, on the data's own datum (EPSG's 326xx/327xx for WGS 84).
std::unique_ptr<OGRSpatialReference> utm_for(const OGRSpatialReference& geographic,
                                             const OGREnvelope& extent) {
  const double lon = 0.5 * (extent.MinX + extent.MaxX);
  const double lat = 0.5 * (extent.MinY + extent.MaxY);
  const int zone = utm_zone(lon);
  const bool north = lat >= 0;
  auto utm = std::make_unique<OGRSpatialReference>();
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  if (geographic.IsSameGeogCS(&wgs84)) {
    utm->importFromEPSG((north ? 32600 : 32700) + zone);
  } else {
    utm->CopyGeogCSFrom(&geographic);
    utm->SetUTM(zone, north ? TRUE : FALSE);
  }
  utm->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return utm;
}

// ---------------------------------------------------------------------------------------------
// One layer, read.

struct Feature {
  int64_t fid;
  MultiPolygonPtr polygons;
};

class LayerReader {
 public:
  LayerReader(const GisImportOptions& o, OGRLayer& layer)
      : o_(o), layer_(layer), where_(o.path + ", layer '" + layer.GetName() + "'") {}

  // Steps 1-2: every feature that passes the filter, as valid polygons in the file's CRS.
  std::vector<Feature> read() {
    if (!o_.where.empty()) {
      CPLErrorReset();
      if (layer_.SetAttributeFilter(o_.where.c_str()) != OGRERR_NONE) {
        throw_invalid("--where", "cannot filter " + where_ + " by " + quote_input(o_.where) + ": " +
                                     QuietGdal::last_message());
      }
    }
    std::vector<Feature> features;
    layer_.ResetReading();
    for (auto& feature : layer_) {
      const int64_t fid = feature->GetFID();
      const OGRGeometry* g = feature->GetGeometryRef();
      if (g == nullptr || g->IsEmpty()) fail(fid, "has no geometry (leave it out with --where)");
      OGRGeometryUniquePtr linear;
      if (g->hasCurveGeometry(TRUE)) {
        linear.reset(g->getLinearGeometry());
        g = linear.get();
      }
      auto polygons = std::make_unique<OGRMultiPolygon>();
      if (!add_polygons(*g, *polygons)) {
        fail(fid,
             std::string("is a ") + OGRGeometryTypeToName(g->getGeometryType()) +
                 (wkbFlatten(g->getGeometryType()) == wkbLineString ? " that is not closed" : "") +
                 "; only polygons, multipolygons and closed line strings are imported");
      }
      polygons->flattenTo2D();
      if (!polygons->IsValid()) fail(fid, "is not a valid polygon: " + invalid_reason(*polygons));
      features.push_back({fid, std::move(polygons)});
    }
    if (features.empty()) {
      throw_invalid(kField, o_.where.empty() ? where_ + " has no features"
                                             : "no feature of " + where_ + " matches --where " +
                                                   quote_input(o_.where));
    }
    return features;
  }

  // Step 3: the output CRS, and the features moved into it.
  std::string reproject(std::vector<Feature>& features) {
    std::unique_ptr<OGRSpatialReference> source;
    if (!o_.from_crs.empty()) {
      source = crs_from_text(o_.from_crs, "--from-crs");
    } else if (const OGRSpatialReference* file_crs = layer_.GetSpatialRef()) {
      source.reset(file_crs->Clone());
      source->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    if (o_.to_crs == "none") {
      return source ? describe(*source) + ", as in the file (not converted)"
                    : "the file's coordinates (no CRS, not converted)";
    }
    OGREnvelope extent;
    for (const Feature& f : features) {
      OGREnvelope e;
      f.polygons->getEnvelope(&e);
      extent.Merge(e);
    }
    if (!source) {
      if (!o_.to_crs.empty()) {
        throw_invalid("--to-crs", where_ + " has no CRS to convert from; give --from-crs");
      }
      if (extent.MinX >= -180 && extent.MaxX <= 180 && extent.MinY >= -90 && extent.MaxY <= 90) {
        throw_invalid(kField, where_ +
                                  " has no CRS and its coordinates lie within longitude and "
                                  "latitude ranges, so they may be degrees; give --from-crs "
                                  "(e.g. EPSG:4326), or --to-crs none to use them as lengths");
      }
      return "the file's coordinates (no CRS)";
    }
    std::unique_ptr<OGRSpatialReference> target;
    if (!o_.to_crs.empty())
      target = crs_from_text(o_.to_crs, "--to-crs");
    else if (source->IsGeographic())
      target = utm_for(*source, extent);
    else
      return describe(*source);
    CPLErrorReset();
    const TransformPtr transform(OGRCreateCoordinateTransformation(source.get(), target.get()));
    const std::string conversion = "from " + describe(*source) + " to " + describe(*target);
    if (!transform) {
      throw_invalid(
          o_.to_crs.empty() ? kField : "--to-crs",
          "cannot convert " + where_ + " " + conversion + ": " + QuietGdal::last_message());
    }
    for (Feature& f : features) {
      CPLErrorReset();
      if (f.polygons->transform(transform.get()) != OGRERR_NONE || !finite(*f.polygons)) {
        fail(f.fid, "cannot be converted " + conversion + ": " +
                        (QuietGdal::last_message().empty() ? "coordinates out of range"
                                                           : QuietGdal::last_message()));
      }
      if (!f.polygons->IsValid()) {
        fail(f.fid, "is not a valid polygon after conversion " + conversion + ": " +
                        invalid_reason(*f.polygons));
      }
    }
    return describe(*target);
  }

  // Steps 4-6 for one feature: clip, simplify, and the rings as vertex lists.
  void finish(const Feature& f, ImportedLayer& out) {
    const OGRGeometry* g = f.polygons.get();
    OGRGeometryUniquePtr clipped, simplified;
    if (o_.clip) {
      const auto& c = *o_.clip;
      OGRLinearRing ring;
      ring.addPoint(c[0], c[1]);
      ring.addPoint(c[2], c[1]);
      ring.addPoint(c[2], c[3]);
      ring.addPoint(c[0], c[3]);
      ring.closeRings();
      OGRPolygon box;
      box.addRing(&ring);
      clipped.reset(g->Intersection(&box));
      if (!clipped) fail(f.fid, "cannot be clipped: " + QuietGdal::last_message());
      g = clipped.get();
    }
    if (o_.simplify_tolerance > 0 && !g->IsEmpty()) {
      simplified.reset(g->SimplifyPreserveTopology(o_.simplify_tolerance));
      if (!simplified) fail(f.fid, "cannot be simplified: " + QuietGdal::last_message());
      g = simplified.get();
    }
    OGRMultiPolygon polygons;
    keep_polygons(*g, polygons);
    const double min_area = o_.simplify_tolerance * o_.simplify_tolerance;
    bool contributed = false;
    for (const OGRPolygon* polygon : polygons) {
      ImportedPolygon p;
      p.fid = f.fid;
      p.outer = ring_vertices(*polygon->getExteriorRing(), min_area);
      const int holes = polygon->getNumInteriorRings();
      if (p.outer.empty()) {
        out.dropped_rings += 1 + holes;
        continue;
      }
      for (int i = 0; i < holes; ++i) {
        std::vector<Vec2> hole = ring_vertices(*polygon->getInteriorRing(i), min_area);
        if (hole.empty())
          ++out.dropped_rings;
        else
          p.holes.push_back(std::move(hole));
      }
      out.polygons.push_back(std::move(p));
      contributed = true;
    }
    out.features += contributed ? 1 : 0;
  }

  const std::string& where() const { return where_; }

 private:
  [[noreturn]] void fail(int64_t fid, const std::string& what) const {
    throw_invalid(kField, where_ + ", feature " + std::to_string(fid) + " " + what);
  }

  static bool finite(const OGRMultiPolygon& g) {
    OGREnvelope e;
    g.getEnvelope(&e);
    return std::isfinite(e.MinX) && std::isfinite(e.MaxX) && std::isfinite(e.MinY) &&
           std::isfinite(e.MaxY);
  }

  const GisImportOptions& o_;
  OGRLayer& layer_;
  std::string where_;  // "file.gpkg, layer 'land'"
};

OGRLayer& pick_layer(GDALDataset& data, const GisImportOptions& o) {
  const std::string& file = o.path;
  if (data.GetLayerCount() == 0) throw_invalid(kField, file + " has no vector layers");
  if (o.layer.empty()) return *data.GetLayer(0);
  if (OGRLayer* layer = data.GetLayerByName(o.layer.c_str())) return *layer;
  std::string names;
  for (OGRLayer* layer : data.GetLayers())
    names += (names.empty() ? "" : ", ") + std::string(layer->GetName());
  throw_invalid("--layer",
                "no layer " + quote_input(o.layer) + " in " + file + "; its layers: " + names);
}

}  // namespace

int utm_zone(double lon_deg) {
  const double lon = std::fmod(std::fmod(lon_deg + 180.0, 360.0) + 360.0, 360.0);  // [0, 360)
  return std::clamp(static_cast<int>(std::floor(lon / 6.0)) + 1, 1, 60);
}

ImportedLayer import_polygons(const GisImportOptions& o) {
  if (o.clip) {
    const auto& c = *o.clip;
    if (!(c[0] < c[2] && c[1] < c[3])) throw_invalid("--clip", "needs xmin < xmax and ymin < ymax");
  }
  if (!(o.simplify_tolerance >= 0 && std::isfinite(o.simplify_tolerance)))
    throw_invalid("--simplify", "the tolerance must be finite and >= 0");
  const QuietGdal quiet;
  std::error_code ignored;
  if (!std::filesystem::exists(o.path, ignored))
    throw_invalid(kField, "cannot open " + quote_input(o.path) + ": no such file or directory");
  const GDALDatasetUniquePtr data(
      GDALDataset::Open(o.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!data) {
    const std::string why = QuietGdal::last_message();
    throw_invalid(kField, "cannot open " + quote_input(o.path) + " as vector data" +
                              (why.empty() ? " (no GDAL driver recognises it)" : ": " + why));
  }
  OGRLayer& layer = pick_layer(*data, o);
  LayerReader reader(o, layer);
  std::vector<Feature> features = reader.read();
  ImportedLayer out;
  out.layer = layer.GetName();
  out.crs = reader.reproject(features);
  for (const Feature& f : features) reader.finish(f, out);
  if (out.polygons.empty()) {
    throw_invalid(kField, out.dropped_rings > 0
                              ? "nothing of " + reader.where() + " is left: simplification made " +
                                    "every ring degenerate (lower --simplify)"
                              : "nothing of " + reader.where() + " lies inside --clip");
  }
  return out;
}

}  // namespace meshd::cli
