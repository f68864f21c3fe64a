// meshctl --import: GIS and CAD files read through GDAL (client/gis_import.h), turned into CSG
// shapes (client/imported_shape.h) and into requests (client/simple_request.h), with every kind
// of bad input. The files are written by the tests: GeoJSON as text, the rest with GDAL.
#include "client/gis_import.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "client/cli_options.h"
#include "client/imported_shape.h"
#include "client/simple_request.h"
#include "core/common/error.h"
#include "core/geometry/polygon_checks.h"
#include "tests/client/gis_test_files.h"

namespace meshd::cli {
namespace {

using meshd::testing::circle;
using meshd::testing::geojson;
using meshd::testing::geojson_feature;
using meshd::testing::geojson_ring;
using meshd::testing::ring_area;
using meshd::testing::square;
using meshd::testing::TempDir;
using meshd::testing::TestLayer;
using meshd::testing::write_text;
using meshd::testing::write_with_gdal;

constexpr int kUtm32N = 32632;  // WGS 84 / UTM zone 32N: metres, so no reprojection
constexpr double kX0 = 500000, kY0 = 5500000;

std::string polygon(const std::vector<std::vector<Vec2>>& rings) {
  std::string text = R"({"type":"Polygon","coordinates":[)";
  for (size_t i = 0; i < rings.size(); ++i) text += (i ? "," : "") + geojson_ring(rings[i]);
  return text + "]}";
}

std::string wkt_polygon(const std::vector<Vec2>& ring) {
  std::string text = "POLYGON((";
  for (const Vec2 p : ring) text += std::to_string(p.x) + " " + std::to_string(p.y) + ",";
  return text + std::to_string(ring[0].x) + " " + std::to_string(ring[0].y) + "))";
}

GisImportOptions options(const std::string& path) {
  GisImportOptions o;
  o.path = path;
  return o;
}

// Runs `f`, which must throw Error(kInvalidArgument) with `field`, and returns the message.
std::string invalid(const std::function<void()>& f, const std::string& field) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

std::vector<Vec2> vertices(const v1::Polygon& p) {
  std::vector<Vec2> v;
  for (const auto& q : p.vertices()) v.push_back({q.x(), q.y()});
  return v;
}

double layer_area(const ImportedLayer& layer) {
  double area = 0;
  for (const auto& p : layer.polygons) {
    area += std::abs(ring_area(p.outer));
    for (const auto& hole : p.holes) area -= std::abs(ring_area(hole));
  }
  return area;
}

// A metric square 100 m wide with a 50 m square hole, as one GeoJSON feature.
std::string square_with_hole(const TempDir& dir) {
  const auto outer = square(kX0, kY0, 100), hole = square(kX0 + 25, kY0 + 25, 50);
  return write_text(
      dir.path("frame.geojson"),
      geojson("frame", {geojson_feature(0, "frame", polygon({outer, hole}))}, kUtm32N));
}

// ---------------------------------------------------------------------------------------------
// What comes in.

TEST(GisImport, SquareWithHoleBecomesADifferenceOfItsRings) {
  TempDir dir;
  const ImportedLayer layer = import_polygons(options(square_with_hole(dir)));
  EXPECT_EQ(layer.layer, "frame");
  EXPECT_NE(layer.crs.find("32632"), std::string::npos) << layer.crs;  // as in the file
  ASSERT_EQ(layer.polygons.size(), 1u);
  EXPECT_EQ(layer.polygons[0].outer, square(kX0, kY0, 100));  // no closing vertex
  ASSERT_EQ(layer.polygons[0].holes.size(), 1u);
  EXPECT_EQ(layer.polygons[0].holes[0], square(kX0 + 25, kY0 + 25, 50));
  EXPECT_EQ(layer.vertices(), 8);
  EXPECT_EQ(layer.dropped_rings, 0);

  const v1::Shape shape = imported_shape(layer, "frame");
  EXPECT_EQ(shape.name(), "frame");
  ASSERT_TRUE(shape.has_difference());
  EXPECT_EQ(vertices(shape.difference().base().polygon()), square(kX0, kY0, 100));
  ASSERT_EQ(shape.difference().subtract_size(), 1);
  EXPECT_EQ(vertices(shape.difference().subtract(0).polygon()), square(kX0 + 25, kY0 + 25, 50));
}

TEST(GisImport, MultipolygonPartsAndFeaturesBecomeOneUnion) {
  TempDir dir;
  const std::string multi = R"({"type":"MultiPolygon","coordinates":[[)" +
                            geojson_ring(square(kX0, kY0, 10)) + "],[" +
                            geojson_ring(square(kX0 + 20, kY0, 10)) + "]]}";
  const std::string path = write_text(
      dir.path("parts.geojson"),
      geojson("parts",
              {geojson_feature(4, "two", multi),
               geojson_feature(
                   9, "one", polygon({square(kX0 + 40, kY0, 30), square(kX0 + 50, kY0 + 10, 10)}))},
              kUtm32N));
  const ImportedLayer layer = import_polygons(options(path));
  ASSERT_EQ(layer.polygons.size(), 3u);
  EXPECT_EQ(layer.features, 2);
  EXPECT_EQ(layer.polygons[0].fid, 4);
  EXPECT_EQ(layer.polygons[1].fid, 4);
  EXPECT_EQ(layer.polygons[2].fid, 9);
  EXPECT_DOUBLE_EQ(layer_area(layer), 100 + 100 + 900 - 100);

  const v1::Shape shape = imported_shape(layer, "parts");
  ASSERT_TRUE(shape.has_union_());
  ASSERT_EQ(shape.union_().shapes_size(), 3);
  EXPECT_EQ(vertices(shape.union_().shapes(0).polygon()), square(kX0, kY0, 10));
  EXPECT_EQ(vertices(shape.union_().shapes(1).polygon()), square(kX0 + 20, kY0, 10));
  EXPECT_TRUE(shape.union_().shapes(2).has_difference());
  EXPECT_EQ(shape.name(), "parts");
}

TEST(GisImport, RepeatedVerticesAndClosedLineStringsAreAccepted) {
  TempDir dir;
  auto ring = square(kX0, kY0, 10);
  ring.insert(ring.begin() + 2, ring[1]);  // a repeated vertex
  const std::string line =
      R"({"type":"LineString","coordinates":)" + geojson_ring(square(kX0 + 20, kY0, 10)) + "}";
  const std::string path = write_text(
      dir.path("lines.geojson"),
      geojson("lines", {geojson_feature(0, "a", polygon({ring})), geojson_feature(1, "b", line)},
              kUtm32N));
  const ImportedLayer layer = import_polygons(options(path));
  ASSERT_EQ(layer.polygons.size(), 2u);
  EXPECT_EQ(layer.polygons[0].outer, square(kX0, kY0, 10));
  EXPECT_EQ(layer.polygons[1].outer, square(kX0 + 20, kY0, 10));
}

TEST(GisImport, WhereFilterKeepsTheMatchingFeatures) {
  TempDir dir;
  std::vector<std::string> features;
  for (int i = 0; i < 3; ++i) {
    features.push_back(geojson_feature(i, std::string(1, static_cast<char>('a' + i)),
                                       polygon({square(kX0 + 20 * i, kY0, 10)})));
  }
  GisImportOptions o =
      options(write_text(dir.path("abc.geojson"), geojson("abc", features, kUtm32N)));
  o.where = "name = 'b'";
  const ImportedLayer layer = import_polygons(o);
  ASSERT_EQ(layer.polygons.size(), 1u);
  EXPECT_EQ(layer.polygons[0].fid, 1);
  EXPECT_EQ(layer.polygons[0].outer, square(kX0 + 20, kY0, 10));
  o.where = "name <> 'b'";
  EXPECT_EQ(import_polygons(o).polygons.size(), 2u);
}

TEST(GisImport, ClipCutsToTheBoxAndLeavesOutWhatLiesOutside) {
  TempDir dir;
  GisImportOptions o = options(
      write_text(dir.path("clip.geojson"),
                 geojson("clip",
                         {geojson_feature(0, "in", polygon({square(kX0, kY0, 100)})),
                          geojson_feature(1, "out", polygon({square(kX0 + 500, kY0, 100)}))},
                         kUtm32N)));
  o.clip = {{kX0 + 50, kY0 - 10, kX0 + 150, kY0 + 40}};
  const ImportedLayer layer = import_polygons(o);
  ASSERT_EQ(layer.polygons.size(), 1u);
  EXPECT_EQ(layer.features, 1);
  EXPECT_NEAR(layer_area(layer), 50 * 40, 1e-6);
  for (const Vec2 p : layer.polygons[0].outer) {
    EXPECT_GE(p.x, kX0 + 50);
    EXPECT_LE(p.x, kX0 + 100);
    EXPECT_GE(p.y, kY0);
    EXPECT_LE(p.y, kY0 + 40);
  }
}

TEST(GisImport, SimplificationReducesVerticesKeepsValidityAndDropsTinyRings) {
  TempDir dir;
  const Vec2 c{kX0, kY0};
  // A wavy 1 km disk of 2,000 vertices with a 300 m lake and a 2 m pond, and a 3 m islet.
  std::vector<Vec2> coast;
  for (int k = 0; k < 2000; ++k) {
    const double t = 2 * M_PI * k / 2000, r = 1000 * (1 + 0.1 * std::sin(7 * t));
    coast.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
  }
  const auto lake = circle({c.x + 200, c.y}, 300, 500);
  const auto pond = square(c.x - 400, c.y, 2);
  const std::string path =
      write_text(dir.path("wavy.geojson"),
                 geojson("wavy",
                         {geojson_feature(0, "land", polygon({coast, lake, pond})),
                          geojson_feature(1, "islet", polygon({square(c.x + 2000, c.y, 3)}))},
                         kUtm32N));
  GisImportOptions o = options(path);
  const ImportedLayer full = import_polygons(o);
  ASSERT_EQ(full.polygons.size(), 2u);
  ASSERT_EQ(full.polygons[0].holes.size(), 2u);

  o.simplify_tolerance = 5;  // metres
  const ImportedLayer simple = import_polygons(o);
  ASSERT_EQ(simple.polygons.size(), 1u);  // the islet is gone
  const ImportedPolygon& land = simple.polygons[0];
  ASSERT_EQ(land.holes.size(), 1u);  // and the pond
  EXPECT_EQ(simple.dropped_rings, 2);
  EXPECT_LT(land.outer.size(), coast.size() / 4);
  EXPECT_LT(land.holes[0].size(), lake.size() / 4);
  EXPECT_GE(land.outer.size(), 20u);
  // What the server will check, and the area kept to within the tolerance along the coast.
  EXPECT_NO_THROW(check_simple_polygon(land.outer, "outer"));
  EXPECT_NO_THROW(check_simple_polygon(land.holes[0], "hole"));
  EXPECT_NEAR(layer_area(simple), layer_area(full), 5 * 2 * M_PI * 1300);
}

// The authalic area of the lon/lat box [lon0, lon1] x [lat0, lat1] on the WGS 84 ellipsoid.
double ellipsoid_box_area(double lon0, double lon1, double lat0, double lat1) {
  const double a = 6378137, f = 1 / 298.257223563, b = a * (1 - f), e2 = f * (2 - f);
  const double e = std::sqrt(e2);
  auto q = [&](double lat_deg) {
    const double s = std::sin(lat_deg * M_PI / 180);
    return s / (1 - e2 * s * s) + std::log((1 + e * s) / (1 - e * s)) / (2 * e);
  };
  return (lon1 - lon0) * M_PI / 180 * b * b / 2 * (q(lat1) - q(lat0));
}

TEST(GisImport, DegreesGoToTheUtmZoneOfTheirCentre) {
  TempDir dir;
  // lon 9.9..10.1, lat 49.9..50.1, every edge cut into 40 (parallels are curves in UTM).
  std::vector<Vec2> ring;
  const std::array<Vec2, 4> corners = {{{9.9, 49.9}, {10.1, 49.9}, {10.1, 50.1}, {9.9, 50.1}}};
  for (int side = 0; side < 4; ++side) {
    const Vec2 a = corners[side], b = corners[(side + 1) % 4];
    for (int k = 0; k < 40; ++k) ring.push_back(a + (k / 40.0) * (b - a));
  }
  const std::string path = write_text(
      dir.path("lonlat.geojson"), geojson("lonlat", {geojson_feature(0, "box", polygon({ring}))}));
  const ImportedLayer layer = import_polygons(options(path));
  EXPECT_NE(layer.crs.find("EPSG:32632"), std::string::npos) << layer.crs;
  EXPECT_NE(layer.crs.find("UTM zone 32N"), std::string::npos) << layer.crs;
  ASSERT_EQ(layer.polygons.size(), 1u);
  for (const Vec2 p : layer.polygons[0].outer) {  // metres east of 9 E and north of the equator
    EXPECT_GT(p.x, 560000);
    EXPECT_LT(p.x, 590000);
    EXPECT_GT(p.y, 5525000);
    EXPECT_LT(p.y, 5555000);
  }
  const double reference = ellipsoid_box_area(9.9, 10.1, 49.9, 50.1);  // about 318 km^2
  EXPECT_NEAR(layer_area(layer) / reference, 1.0, 0.005)
      << layer_area(layer) << " m^2 against " << reference;

  GisImportOptions o = options(path);
  o.to_crs = "EPSG:3035";  // ETRS89-extended / LAEA Europe: equal-area
  const ImportedLayer laea = import_polygons(o);
  EXPECT_NE(laea.crs.find("3035"), std::string::npos) << laea.crs;
  EXPECT_NEAR(layer_area(laea) / reference, 1.0, 0.001);
  o.to_crs = "none";
  EXPECT_EQ(import_polygons(o).polygons[0].outer[0], (Vec2{9.9, 49.9}));
}

TEST(GisImport, UtmZones) {
  EXPECT_EQ(utm_zone(10), 32);
  EXPECT_EQ(utm_zone(-35), 25);
  EXPECT_EQ(utm_zone(-180), 1);
  EXPECT_EQ(utm_zone(179.9), 60);
  EXPECT_EQ(utm_zone(180), 1);  // wraps to -180
  EXPECT_EQ(utm_zone(0), 31);
}

TEST(GisImport, SouthernHemisphereGoesToTheSouthernZone) {
  TempDir dir;
  const std::string path = write_text(
      dir.path("south.geojson"),
      geojson("south", {geojson_feature(0, "box", polygon({square(151.0, -34.0, 0.1)}))}));
  const ImportedLayer layer = import_polygons(options(path));
  EXPECT_NE(layer.crs.find("EPSG:32756"), std::string::npos) << layer.crs;
  EXPECT_GT(layer.polygons[0].outer[0].y, 6e6);  // false northing 10,000 km
}

TEST(GisImport, ShapefileGeoPackageAndDxfReadLikeGeoJson) {
  TempDir dir;
  const auto outer = square(kX0, kY0, 100);
  const std::string wkt =
      "POLYGON((500000 5500000,500100 5500000,500100 5500100,500000 5500100,"
      "500000 5500000),(500025 5500025,500025 5500075,500075 5500075,"
      "500075 5500025,500025 5500025))";
  const std::vector<TestLayer> layers = {{"frame", kUtm32N, {{wkt, "frame"}}}};
  const ImportedLayer reference = import_polygons(options(square_with_hole(dir)));
  for (const auto& [file, driver] : std::vector<std::pair<std::string, std::string>>{
           {"frame.shp", "ESRI Shapefile"}, {"frame.gpkg", "GPKG"}, {"frame.kml", "KML"}}) {
    SCOPED_TRACE(driver);
    GisImportOptions o = options(write_with_gdal(dir.path(file), driver, layers));
    if (driver == "KML") o.to_crs = "EPSG:32632";  // KML is always lon/lat
    const ImportedLayer layer = import_polygons(o);
    ASSERT_EQ(layer.polygons.size(), 1u);
    ASSERT_EQ(layer.polygons[0].holes.size(), 1u);
    EXPECT_EQ(layer.polygons[0].outer.size(), 4u);
    EXPECT_NEAR(layer_area(layer), layer_area(reference), 0.5);  // KML keeps ~1e-9 degrees
    for (const Vec2 p : layer.polygons[0].outer) {               // the same corners, in some order
      EXPECT_NE(
          std::find_if(outer.begin(), outer.end(), [&](Vec2 q) { return norm(p - q) < 1e-2; }),
          outer.end());
    }
  }
  // DXF has no CRS and stores the outline as a closed polyline or a hatch.
  GisImportOptions o = options(
      write_with_gdal(dir.path("frame.dxf"), "DXF", {{"entities", 0, {{wkt_polygon(outer), ""}}}}));
  const ImportedLayer layer = import_polygons(o);
  ASSERT_EQ(layer.polygons.size(), 1u);
  EXPECT_NEAR(layer_area(layer), 100 * 100, 1e-6);
  EXPECT_NE(layer.crs.find("no CRS"), std::string::npos) << layer.crs;
}

TEST(GisImport, LayerChoice) {
  TempDir dir;
  const std::string path =
      write_with_gdal(dir.path("two.gpkg"), "GPKG",
                      {{"land", kUtm32N, {{wkt_polygon(square(kX0, kY0, 10)), "a"}}},
                       {"water", kUtm32N, {{wkt_polygon(square(kX0, kY0, 30)), "b"}}}});
  GisImportOptions o = options(path);
  EXPECT_EQ(import_polygons(o).layer, "land");  // the first
  o.layer = "water";
  const ImportedLayer water = import_polygons(o);
  EXPECT_EQ(water.layer, "water");
  EXPECT_DOUBLE_EQ(layer_area(water), 900);
  o.layer = "air";
  const std::string message = invalid([&] { import_polygons(o); }, "--layer");
  EXPECT_NE(message.find("'air'"), std::string::npos) << message;
  EXPECT_NE(message.find("its layers: land, water"), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------------------
// Every bad input: an INVALID_ARGUMENT that names the flag, the file and the feature.

TEST(GisImportErrors, FileCannotBeOpened) {
  TempDir dir;
  const std::string missing = dir.path("missing.gpkg");
  std::string m = invalid([&] { import_polygons(options(missing)); }, "--import");
  EXPECT_NE(m.find("missing.gpkg"), std::string::npos) << m;
  EXPECT_NE(m.find("no such file"), std::string::npos) << m;
  const std::string junk = write_text(dir.path("junk.bin"), "not a map\n");
  m = invalid([&] { import_polygons(options(junk)); }, "--import");
  EXPECT_NE(m.find("junk.bin"), std::string::npos) << m;
  EXPECT_NE(m.find("cannot open"), std::string::npos) << m;
}

TEST(GisImportErrors, EmptyLayerAndEmptyAfterFilterOrClip) {
  TempDir dir;
  const std::string empty = write_text(dir.path("empty.geojson"), geojson("empty", {}, kUtm32N));
  std::string m = invalid([&] { import_polygons(options(empty)); }, "--import");
  EXPECT_NE(m.find("empty.geojson, layer 'empty' has no features"), std::string::npos) << m;

  GisImportOptions o = options(square_with_hole(dir));
  o.where = "name = 'nothing'";
  m = invalid([&] { import_polygons(o); }, "--import");
  EXPECT_NE(m.find("no feature of"), std::string::npos) << m;
  EXPECT_NE(m.find("matches --where"), std::string::npos) << m;

  o.where.clear();
  o.clip = {{0, 0, 1, 1}};
  m = invalid([&] { import_polygons(o); }, "--import");
  EXPECT_NE(m.find("lies inside --clip"), std::string::npos) << m;
}

TEST(GisImportErrors, GeometryThatIsNotPolygonal) {
  TempDir dir;
  const std::string point = R"({"type":"Point","coordinates":[500000,5500000]})";
  std::string m = invalid(
      [&] {
        import_polygons(
            options(write_text(dir.path("points.geojson"),
                               geojson("points",
                                       {geojson_feature(0, "ok", polygon({square(kX0, kY0, 1)})),
                                        geojson_feature(7, "pt", point)},
                                       kUtm32N))));
      },
      "--import");
  EXPECT_NE(m.find("points.geojson, layer 'points', feature 7 is a Point"), std::string::npos) << m;
  const std::string open_line = R"({"type":"LineString","coordinates":[[0,0],[1,0],[1,1]]})";
  m = invalid(
      [&] {
        import_polygons(
            options(write_text(dir.path("line.geojson"),
                               geojson("line", {geojson_feature(3, "l", open_line)}, kUtm32N))));
      },
      "--import");
  EXPECT_NE(m.find("feature 3 is a Line String that is not closed"), std::string::npos) << m;
  m = invalid(
      [&] {
        import_polygons(
            options(write_text(dir.path("null.geojson"),
                               geojson("null", {geojson_feature(5, "n", "null")}, kUtm32N))));
      },
      "--import");
  EXPECT_NE(m.find("feature 5 has no geometry"), std::string::npos) << m;
}

TEST(GisImportErrors, SelfIntersectingRing) {
  TempDir dir;
  const std::vector<Vec2> bowtie = {
      {kX0, kY0}, {kX0 + 10, kY0 + 10}, {kX0 + 10, kY0}, {kX0, kY0 + 10}};
  const std::string m = invalid(
      [&] {
        import_polygons(options(write_text(
            dir.path("bowtie.geojson"),
            geojson("bowtie", {geojson_feature(12, "bow", polygon({bowtie}))}, kUtm32N))));
      },
      "--import");
  EXPECT_NE(m.find("bowtie.geojson, layer 'bowtie', feature 12 is not a valid polygon: "
                   "Self-intersection"),
            std::string::npos)
      << m;
  // A hole that sticks out of its polygon: valid rings, invalid polygon.
  const std::string m2 = invalid(
      [&] {
        import_polygons(options(write_text(
            dir.path("hole.geojson"),
            geojson("hole",
                    {geojson_feature(
                        2, "h", polygon({square(kX0, kY0, 10), square(kX0 + 5, kY0 + 5, 10)}))},
                    kUtm32N))));
      },
      "--import");
  EXPECT_NE(m2.find("feature 2 is not a valid polygon"), std::string::npos) << m2;
}

TEST(GisImportErrors, CrsThatCannotBeConverted) {
  TempDir dir;
  // A shapefile without .prj whose coordinates could be degrees.
  const std::string shp =
      write_with_gdal(dir.path("nocrs.shp"), "ESRI Shapefile",
                      {{"nocrs", 0, {{wkt_polygon(square(10, 50, 0.1)), "x"}}}});
  std::string m = invalid([&] { import_polygons(options(shp)); }, "--import");
  EXPECT_NE(m.find("has no CRS"), std::string::npos) << m;
  EXPECT_NE(m.find("--from-crs"), std::string::npos) << m;
  GisImportOptions o = options(shp);
  o.to_crs = "EPSG:32632";
  m = invalid([&] { import_polygons(o); }, "--to-crs");
  EXPECT_NE(m.find("no CRS to convert from"), std::string::npos) << m;
  o.from_crs = "EPSG:4326";  // what the user knows: now it converts
  EXPECT_NEAR(layer_area(import_polygons(o)), ellipsoid_box_area(10, 10.1, 50, 50.1),
              0.005 * ellipsoid_box_area(10, 10.1, 50, 50.1));
  o = options(shp);
  o.to_crs = "none";  // or: they are lengths
  EXPECT_NEAR(layer_area(import_polygons(o)), 0.1 * 0.1, 1e-12);

  o = options(square_with_hole(dir));
  o.to_crs = "EPSG:99999999";
  m = invalid([&] { import_polygons(o); }, "--to-crs");
  EXPECT_NE(m.find("not a coordinate reference system"), std::string::npos) << m;
  o.to_crs.clear();
  o.from_crs = "no such thing";
  invalid([&] { import_polygons(o); }, "--from-crs");

  // The far side of the globe has no orthographic coordinates: that feature fails to convert.
  const std::string far =
      write_text(dir.path("far.geojson"),
                 geojson("far", {geojson_feature(0, "near", polygon({square(0, 0, 1)})),
                                 geojson_feature(6, "far", polygon({square(170, 0, 1)}))}));
  o = options(far);
  o.to_crs = "+proj=ortho +lat_0=0 +lon_0=0 +datum=WGS84";
  m = invalid([&] { import_polygons(o); }, "--import");
  EXPECT_NE(m.find("far.geojson, layer 'far', feature 6 cannot be converted from"),
            std::string::npos)
      << m;
}

TEST(GisImportErrors, BadWhere) {
  TempDir dir;
  GisImportOptions o = options(square_with_hole(dir));
  o.where = "height >";
  const std::string m = invalid([&] { import_polygons(o); }, "--where");
  EXPECT_NE(m.find("frame.geojson, layer 'frame'"), std::string::npos) << m;
}

TEST(GisImportErrors, BadClipNumbers) {
  for (const std::string clip :
       {"1,2,3", "1,2,3,4,5", "a,0,1,1", "0,0,1,nan", "1,0,0,1", "0,1,1,1", ""}) {
    SCOPED_TRACE(clip);
    invalid([&] { parse_cli({"generate", "--import", "x.shp", "--clip", clip}); }, "--clip");
  }
  const CliOptions o = parse_cli({"generate", "--clip", "-1.5,2,3e3,4"});
  ASSERT_TRUE(o.gis.clip.has_value());
  EXPECT_EQ(*o.gis.clip, (std::array<double, 4>{-1.5, 2, 3000, 4}));
  invalid([&] { parse_cli({"generate", "--simplify", "0"}); }, "--simplify");
}

// ---------------------------------------------------------------------------------------------
// Into a request.

TEST(GisImportRequest, ImportAloneOrSubtractedFromTheClipBox) {
  TempDir dir;
  const std::string path = square_with_hole(dir);
  CliOptions o = parse_cli({"generate", "--import", path, "--h0", "5"});
  v1::MeshRequest request = build_request(o);
  EXPECT_EQ(request.h0(), 5);
  ASSERT_TRUE(request.geometry().has_difference());
  EXPECT_EQ(request.geometry().name(), "frame");

  o = parse_cli({"generate", "--import", path, "--h0", "5", "--clip",
                 "499990,5499990,500050,5500200", "--subtract-from-clip", "--import-name",
                 "coast"});
  std::string summary;
  request = build_request(o, &summary);
  const auto& d = request.geometry().difference();
  ASSERT_TRUE(d.base().has_rectangle());
  EXPECT_EQ(d.base().name(), "clip");
  EXPECT_EQ(d.base().rectangle().min().x(), 499990);
  EXPECT_EQ(d.base().rectangle().max().y(), 5500200);
  ASSERT_EQ(d.subtract_size(), 1);
  EXPECT_EQ(d.subtract(0).name(), "coast");
  // The clipped frame: x in [500000, 500050], the hole cut open on its right.
  EXPECT_TRUE(d.subtract(0).has_difference() || d.subtract(0).has_polygon());
  EXPECT_NE(summary.find("imported 1 polygon (0 holes"), std::string::npos) << summary;
  EXPECT_NE(summary.find("as group 'coast'"), std::string::npos) << summary;

  invalid([&] { build_request(parse_cli({"generate", "--import", path})); }, "--h0");
  invalid(
      [&] {
        build_request(
            parse_cli({"generate", "--import", path, "--h0", "1", "--subtract-from-clip"}));
      },
      "--subtract-from-clip");
  invalid(
      [&] {
        build_request(parse_cli({"generate", "--circle", "1", "--h0", "1", "--layer", "x"}));
      },
      "--layer");
  invalid(
      [&] {
        build_request(parse_cli({"generate", "--import", path, "--circle", "1", "--h0", "1"}));
      },
      "--import");
}

TEST(GisImportRequest, SimplifyToleranceIsTimesH0) {
  TempDir dir;
  std::vector<Vec2> coast = circle({kX0, kY0}, 1000, 1000);
  const std::string path =
      write_text(dir.path("disk.geojson"),
                 geojson("disk", {geojson_feature(0, "d", polygon({coast}))}, kUtm32N));
  auto polygon_size = [&](const char* h0, const char* f) {
    const v1::MeshRequest r =
        build_request(parse_cli({"generate", "--import", path, "--h0", h0, "--simplify", f}));
    return r.geometry().polygon().vertices_size();
  };
  // Tolerance 1 m against 10 m: the sagitta rule gives ~ pi / sqrt(2 tol / r) vertices.
  const int fine = polygon_size("10", "0.1"), coarse = polygon_size("100", "0.1");
  EXPECT_LT(fine, 1000);
  EXPECT_LT(coarse, fine / 2);
  EXPECT_GE(coarse, 10);
}

TEST(GisImportRequest, GradeAddsADistanceTermAboutTheImport) {
  TempDir dir;
  const std::string path = square_with_hole(dir);
  const v1::MeshRequest request = build_request(
      parse_cli({"generate", "--import", path, "--h0", "5", "--clip",
                 "499990,5499990,500050,5500200", "--subtract-from-clip", "--grade", "1,0.02,6"}));
  ASSERT_EQ(request.size().terms_size(), 1);
  const v1::DistanceSize& term = request.size().terms(0).distance();
  EXPECT_EQ(term.h_min(), 1);
  EXPECT_EQ(term.slope(), 0.02);
  EXPECT_EQ(term.h_max(), 6);
  // The same shape as the one subtracted from the clip box.
  EXPECT_EQ(term.shape().SerializeAsString(),
            request.geometry().difference().subtract(0).SerializeAsString());

  for (const std::string grade : {"1,0.02", "0,0.02,6", "1,-1,6", "2,0.1,1", "1,x,2"}) {
    SCOPED_TRACE(grade);
    invalid([&] { parse_cli({"generate", "--import", path, "--grade", grade}); }, "--grade");
  }
  invalid(
      [&] {
        build_request(parse_cli({"generate", "--circle", "1", "--h0", "1", "--grade", "1,0.1,2"}));
      },
      "--grade");
}

TEST(GisImportRequest, PlaceholdersOfARequestFileAreFilled) {
  TempDir dir;
  const std::string shape_path = square_with_hole(dir);
  const std::string request_path = write_text(dir.path("sea.textproto"), R"(
geometry {
  difference {
    base { name: "sea" rectangle { min { x: 499000 y: 5499000 } max { x: 501000 y: 5501000 } } }
    subtract { name: "frame" }
  }
}
size { terms { distance { shape { name: "frame" } h_min: 1 slope: 0.01 h_max: 4 } } }
h0: 20
)");
  const v1::MeshRequest request =
      build_request(parse_cli({"generate", request_path, "--import", shape_path}));
  EXPECT_EQ(request.h0(), 20);
  const v1::Shape& filled = request.geometry().difference().subtract(0);
  ASSERT_TRUE(filled.has_difference());
  EXPECT_EQ(filled.name(), "frame");
  EXPECT_EQ(vertices(filled.difference().base().polygon()), square(kX0, kY0, 100));
  EXPECT_TRUE(request.size().terms(0).distance().shape().has_difference());
  EXPECT_EQ(request.geometry().difference().base().name(), "sea");

  // Under another name the file's placeholders do not match.
  const std::string m = invalid(
      [&] {
        build_request(
            parse_cli({"generate", request_path, "--import", shape_path, "--import-name", "x"}));
      },
      "request");
  EXPECT_NE(m.find("no placeholder"), std::string::npos) << m;
  EXPECT_NE(m.find("name: \"x\""), std::string::npos) << m;
}

TEST(GisImportRequest, ReplacePlaceholdersWalksTheWholeTree) {
  v1::MeshRequest request;
  auto* rotate = request.mutable_geometry()->mutable_rotate();
  auto* shapes = rotate->mutable_shape()->mutable_union_()->mutable_shapes();
  shapes->Add()->set_name("land");
  shapes->Add()->mutable_circle()->set_radius(1);
  shapes->Add()->set_name("other");
  shapes->Add()->mutable_translate()->mutable_shape()->set_name("land");
  v1::Shape land;
  land.mutable_circle()->set_radius(7);
  land.set_name("land");
  EXPECT_EQ(replace_placeholders(request, "land", land), 2);
  EXPECT_FALSE(request.has_size());  // not created on the way
  const auto& u = request.geometry().rotate().shape().union_();
  EXPECT_EQ(u.shapes(0).circle().radius(), 7);
  EXPECT_EQ(u.shapes(1).circle().radius(), 1);
  EXPECT_EQ(u.shapes(2).kind_case(), v1::Shape::KIND_NOT_SET);
  EXPECT_EQ(u.shapes(3).translate().shape().circle().radius(), 7);
  EXPECT_EQ(replace_placeholders(request, "land", land), 0);  // none left
}

}  // namespace
}  // namespace meshd::cli
