#include "tests/client/gis_test_files.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace meshd::testing {

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "meshd_gis_XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  dir_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(dir_, ignored);
}

std::string geojson_ring(const std::vector<Vec2>& ring) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (const Vec2 p : ring) out << "[" << p.x << "," << p.y << "],";
  out << "[" << ring[0].x << "," << ring[0].y << "]]";
  return out.str();
}

std::string geojson_feature(int fid, const std::string& name, const std::string& geometry) {
  return R"({"type":"Feature","id":)" + std::to_string(fid) + R"(,"properties":{"name":")" + name +
         R"("},"geometry":)" + geometry + "}";
}

std::string geojson(const std::string& layer, const std::vector<std::string>& features, int epsg) {
  std::string text = R"({"type":"FeatureCollection","name":")" + layer + "\",";
  if (epsg > 0) {
    text += R"("crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::)" +
            std::to_string(epsg) + "\"}},";
  }
  text += "\"features\":[";
  for (size_t i = 0; i < features.size(); ++i) text += (i ? "," : "") + features[i];
  return text + "]}";
}

std::string write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

std::string write_with_gdal(const std::string& path, const std::string& driver_name,
                            const std::vector<TestLayer>& layers) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name.c_str());
  if (driver == nullptr) {
    ADD_FAILURE() << "no GDAL driver " << driver_name;
    return path;
  }
  GDALDatasetUniquePtr data(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!data) {
    ADD_FAILURE() << "cannot create " << path << ": " << CPLGetLastErrorMsg();
    return path;
  }
  for (const TestLayer& l : layers) {
    OGRSpatialReference srs;
    if (l.epsg > 0) {
      srs.importFromEPSG(l.epsg);
      srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    OGRLayer* layer =
        data->CreateLayer(l.name.c_str(), l.epsg > 0 ? &srs : nullptr, wkbUnknown, nullptr);
    if (layer == nullptr) {
      ADD_FAILURE() << "cannot create layer " << l.name << ": " << CPLGetLastErrorMsg();
      continue;
    }
    if (driver_name != "DXF") {
      OGRFieldDefn field("name", OFTString);
      layer->CreateField(&field);
    }
    for (const auto& [wkt, name] : l.features) {
      OGRFeature feature(layer->GetLayerDefn());
      if (driver_name != "DXF") feature.SetField("name", name.c_str());
      OGRGeometry* geometry = nullptr;
      if (OGRGeometryFactory::createFromWkt(wkt.c_str(), nullptr, &geometry) != OGRERR_NONE) {
        ADD_FAILURE() << "bad WKT " << wkt;
        continue;
      }
      feature.SetGeometryDirectly(geometry);
      if (layer->CreateFeature(&feature) != OGRERR_NONE)
        ADD_FAILURE() << "cannot write a feature to " << path << ": " << CPLGetLastErrorMsg();
    }
  }
  return path;
}

std::vector<Vec2> square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

std::vector<Vec2> circle(Vec2 c, double r, int n) {
  std::vector<Vec2> ring;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * k / n;
    ring.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
  }
  return ring;
}

double ring_area(const std::vector<Vec2>& ring) {
  double twice = 0;
  for (size_t i = 1; i + 1 < ring.size(); ++i)
    twice += cross(ring[i] - ring[0], ring[i + 1] - ring[0]);
  return twice / 2;
}

}  // namespace meshd::testing
