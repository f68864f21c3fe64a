#include "core/mesh/svg_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

#include "core/common/error.h"
#include "core/mesh/quality.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

std::string write(const Mesh& mesh, const SvgOptions& options = {}) {
  std::ostringstream out;
  write_svg(mesh, out, options);
  return out.str();
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + what.size())) ++n;
  return n;
}

// The number of closed sub-paths ('z') in the filled <path> elements: one per triangle.
size_t filled_triangles(const std::string& svg) {
  size_t n = 0;
  for (size_t at = svg.find("<path fill=\"#"); at != std::string::npos;
       at = svg.find("<path fill=\"#", at + 1)) {
    const size_t d = svg.find(" d=\"", at) + 4;
    const size_t end = svg.find('"', d);
    n += static_cast<size_t>(std::count(svg.begin() + d, svg.begin() + end, 'z'));
  }
  return n;
}

TEST(WriteSvg, DrawsEveryTriangleOnceAndTheBoundaryPerGroup) {
  const Mesh mesh = testing::structured_square_mesh(8, 6, 2.0, 1.0);
  const std::string svg = write(mesh);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(count(svg, "<svg "), 1u);
  EXPECT_NE(svg.find("width=\"800\""), std::string::npos);
  EXPECT_NE(svg.find("viewBox=\"0 0 8000 "), std::string::npos);
  EXPECT_EQ(filled_triangles(svg), mesh.triangles.size());
  // Structured triangles are congruent: a single colour bin, so a single filled path.
  EXPECT_EQ(count(svg, "<path fill=\"#"), 1u);
  // Four boundary groups: one stroked path each, and legend entries with their names.
  EXPECT_EQ(count(svg, "<path stroke="), 4u);
  for (const auto& name : mesh.boundary_names) {
    EXPECT_NE(svg.find(">" + name + "</text>"), std::string::npos) << name;
  }
  const QualityStats stats = summarize_quality(mesh);
  char expected[64];
  std::snprintf(expected, sizeof(expected), "q_min %.3f, q_mean %.3f", stats.q_min, stats.q_mean);
  EXPECT_NE(svg.find(expected), std::string::npos) << expected;
  // Large triangles: edges drawn in grey.
  EXPECT_NE(svg.find("stroke=\"#303030\""), std::string::npos);
}

TEST(WriteSvg, YAxisPointsUp) {
  // The top side (y = 1) must be drawn above (smaller SVG y than) the bottom side (y = 0).
  const Mesh mesh = testing::structured_square_mesh(1, 1);
  const std::string svg = write(mesh, {.width_px = 100, .margin = 0.0, .legend = false});
  // Group paths are in boundary_names order: left, right, bottom, top. Each starts "M x y".
  auto start_y = [&](int group) {
    size_t at = 0;
    for (int g = 0; g <= group; ++g) at = svg.find("<path stroke=", at + 1);
    at = svg.find("d=\"M", at) + 4;
    std::istringstream in(svg.substr(at, 40));
    long x, y;
    in >> x >> y;
    return y;
  };
  EXPECT_EQ(start_y(testing::kBottom), 1000);  // 100 px * 10 grid units, at the bottom
  EXPECT_EQ(start_y(testing::kTop), 0);
}

TEST(WriteSvg, SizeStaysSmallPerTriangleAndEdgesDisappearWhenTiny) {
  const Mesh mesh = testing::structured_square_mesh(300, 300);  // 180k triangles
  const std::string svg = write(mesh);
  EXPECT_EQ(filled_triangles(svg), mesh.triangles.size());
  EXPECT_LT(svg.size(), 30 * mesh.triangles.size());
  // One bin (congruent triangles), split into paths of at most 10,000 triangles for parsers.
  EXPECT_EQ(count(svg, "<path fill=\"#"), 18u);
  EXPECT_EQ(svg.find("stroke=\"#303030\""), std::string::npos);
}

TEST(WriteSvg, QualityBinsGetDifferentColours) {
  Mesh mesh = testing::structured_square_mesh(2, 1);
  mesh.points[1].x = 0.95;  // squeezes the two left triangles, stretches the right ones
  const std::string svg = write(mesh);
  EXPECT_GE(count(svg, "<path fill=\"#"), 2u);
  EXPECT_EQ(filled_triangles(svg), 4u);
}

TEST(WriteSvg, EmptyMeshAndDegenerateBoxAreFine) {
  EXPECT_NE(write(Mesh{}).find("</svg>"), std::string::npos);
  Mesh line;
  line.points = {{0, 0}, {0, 1}, {0, 2}};  // zero width
  line.triangles = {{0, 1, 2}};
  const std::string svg = write(line);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(WriteSvg, BadIndicesThrow) {
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.boundary_edges[0][0] = -1;
  EXPECT_THROW(write(mesh), Error);
}

}  // namespace
}  // namespace meshd
