// meshctl --import end to end: examples/gis/island.geojson imported as meshctl does it
// (build_request), meshed by a real meshd service in process (tests/server/test_server.h), and
// the mesh checked: valid, the imported coast among its boundary groups, its area that of the
// domain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "client/cli_options.h"
#include "client/gis_import.h"
#include "client/result_assembly.h"
#include "client/simple_request.h"
#include "core/mesh/validity.h"
#include "tests/server/test_server.h"

namespace meshd::cli {
namespace {

const std::string kExamples = std::string(MESHD_SOURCE_DIR) + "/examples/gis/";

double polygons_area(const ImportedLayer& layer) {
  auto area = [](const std::vector<Vec2>& r) {
    double twice = 0;
    for (size_t i = 1; i + 1 < r.size(); ++i) twice += cross(r[i] - r[0], r[i + 1] - r[0]);
    return std::abs(twice) / 2;
  };
  double total = 0;
  for (const auto& p : layer.polygons) {
    total += area(p.outer);
    for (const auto& hole : p.holes) total -= area(hole);
  }
  return total;
}

Mesh generate_mesh(const v1::MeshRequest& request) {
  meshd::testing::TestServer server;
  auto stub = server.stub();
  const auto result = meshd::testing::generate(*stub, request, std::chrono::seconds(120));
  EXPECT_TRUE(result.status.ok()) << result.status.error_message();
  EXPECT_TRUE(result.has_done);
  EXPECT_TRUE(result.checksum_ok);
  return to_mesh(result.mesh);
}

bool has_group(const Mesh& mesh, const std::string& name) {
  return std::find(mesh.boundary_names.begin(), mesh.boundary_names.end(), name) !=
         mesh.boundary_names.end();
}

TEST(GisGenerate, TheIslandMeshes) {
  const std::string island = kExamples + "island.geojson";
  CliOptions o = parse_cli(
      {"generate", "--import", island, "--h0", "600", "--simplify", "0.25", "--backend", "cpu"});
  const v1::MeshRequest request = build_request(o);
  const Mesh mesh = generate_mesh(request);
  const ValidityReport report = check_validity(mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems[0]);
  EXPECT_GT(mesh.points.size(), 500u);
  EXPECT_TRUE(has_group(mesh, "island"));

  GisImportOptions gis;
  gis.path = island;
  gis.simplify_tolerance = 0.25 * 600;
  const double domain = polygons_area(import_polygons(gis));
  EXPECT_NEAR(mesh_area(mesh) / domain, 1.0, 0.02);  // polygons' chords against the boundary
}

TEST(GisGenerate, TheSeaAroundTheIslandMeshesGraded) {
  // The example request (a box minus the island, graded toward the coast) at a larger h0.
  CliOptions o = parse_cli({"generate", kExamples + "island_ocean.textproto", "--import",
                            kExamples + "island.geojson", "--h0", "1000", "--backend", "cpu"});
  const v1::MeshRequest request = build_request(o);
  ASSERT_TRUE(request.geometry().difference().subtract(0).has_union_());
  const Mesh mesh = generate_mesh(request);
  const ValidityReport report = check_validity(mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems[0]);
  EXPECT_TRUE(has_group(mesh, "island"));
  EXPECT_TRUE(has_group(mesh, "sea"));

  GisImportOptions gis;
  gis.path = kExamples + "island.geojson";
  const double sea = 100e3 * 75e3 - polygons_area(import_polygons(gis));
  EXPECT_NEAR(mesh_area(mesh) / sea, 1.0, 0.01);
  // Graded: edges at the coast are shorter than edges along the box.
  auto mean_edge = [&](const std::string& group) {
    const auto g = std::find(mesh.boundary_names.begin(), mesh.boundary_names.end(), group) -
                   mesh.boundary_names.begin();
    double sum = 0;
    int n = 0;
    for (size_t e = 0; e < mesh.boundary_edges.size(); ++e) {
      if (mesh.boundary_tags[e] != g) continue;
      sum += norm(mesh.points[mesh.boundary_edges[e][1]] - mesh.points[mesh.boundary_edges[e][0]]);
      ++n;
    }
    return sum / std::max(n, 1);
  };
  EXPECT_LT(2 * mean_edge("island"), mean_edge("sea"));
}

}  // namespace
}  // namespace meshd::cli
