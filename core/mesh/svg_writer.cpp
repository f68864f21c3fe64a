#include "core/mesh/svg_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/mesh/quality.h"
#include "core/mesh/quality_colours.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"
#include "core/mesh/xml_escaped.h"

namespace meshd {
namespace {

constexpr int kSubpixels = 10;   // grid units per pixel
constexpr int kColourBins = 20;  // quality bins, each one colour
// librsvg (libxml2) rejects attribute values past a few megabytes, so a bin's triangles are split
// over paths of at most this many (about 250 kB of path data each).
constexpr size_t kMaxTrianglesPerPath = 10000;
constexpr double kMinEdgePx = 4;  // draw triangle edges only when the mean edge is this long
constexpr double kLegendRowPx = 22;

std::string bin_colour(int bin) { return hex(quality_colour((bin + 0.5) / kColourBins)); }

// Boundary groups cycle through these (dark enough to stand out against the fill).
constexpr const char* kGroupColours[] = {"#000000", "#e7298a", "#7570b3", "#d95f02",
                                         "#1b9e77", "#666666", "#a6761d", "#e6ab02"};
constexpr int kNumGroupColours = sizeof(kGroupColours) / sizeof(kGroupColours[0]);

// Maps mesh coordinates to the integer grid, y up.
struct Transform {
  double min_x, max_y, scale, offset_x, offset_y;  // scale in grid units per length unit
  std::array<int64_t, 2> operator()(Vec2 p) const {
    return {std::llround(offset_x + (p.x - min_x) * scale),
            std::llround(offset_y + (max_y - p.y) * scale)};
  }
};

// Writes a relative move "dx dy" with the fewest separators SVG's path grammar allows: a minus
// sign separates numbers by itself.
void relative(TextBuffer& b, int64_t dx, int64_t dy, bool after_number) {
  if (after_number && dx >= 0) b.character(' ');
  b.number(dx);
  if (dy >= 0) b.character(' ');
  b.number(dy);
}

}  // namespace

void write_svg(const Mesh& mesh, std::ostream& out, const SvgOptions& options) {
  check_indices(mesh);
  const double width_px = std::max(options.width_px, 16);
  const double margin_px = std::clamp(options.margin, 0.0, 0.4) * width_px;

  // ---- Fit the mesh's bounding box into the drawing area ----
  double min_x = 0, min_y = 0, max_x = 1, max_y = 1;
  if (!mesh.points.empty()) {
    min_x = max_x = mesh.points[0].x;
    min_y = max_y = mesh.points[0].y;
    for (const Vec2 p : mesh.points) {
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
  }
  const double draw_px = width_px - 2 * margin_px;
  const double box_w = max_x - min_x, box_h = max_y - min_y;
  // Tall meshes are capped at twice the width so that the picture stays on a screen.
  double px_per_unit =
      std::min(box_w > 0 ? draw_px / box_w : HUGE_VAL, box_h > 0 ? 2 * draw_px / box_h : HUGE_VAL);
  if (!std::isfinite(px_per_unit)) px_per_unit = 1.0;
  const double mesh_h_px = box_h * px_per_unit;
  const double legend_px =
      options.legend ? (mesh.boundary_names.empty() ? 1 : 2) * kLegendRowPx : 0;
  const double height_px = std::ceil(mesh_h_px + 2 * margin_px + legend_px);
  const Transform to_grid{min_x, max_y, px_per_unit * kSubpixels,
                          (margin_px + 0.5 * (draw_px - box_w * px_per_unit)) * kSubpixels,
                          margin_px * kSubpixels};

  const std::vector<double> quality = triangle_quality(mesh);
  const QualityStats stats = summarize_quality(mesh);

  TextBuffer b(out);
  b.text("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  b.text("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"").number(width_px);
  b.text("\" height=\"").number(height_px).text("\" viewBox=\"0 0 ");
  b.number(std::llround(width_px * kSubpixels)).character(' ');
  b.number(std::llround(height_px * kSubpixels)).text("\">\n");
  b.text("<title>").number(mesh.points.size()).text(" points, ").number(mesh.triangles.size());
  b.text(" triangles, ").number(mesh.boundary_edges.size()).text(" boundary edges</title>\n");
  b.text("<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");

  // ---- Triangles, one path per quality bin ----
  double edge_sum = 0;
  for (const auto& t : mesh.triangles) {
    edge_sum += norm(mesh.points[t[1]] - mesh.points[t[0]]);
  }
  const double mean_edge_px =
      mesh.triangles.empty() ? 0 : edge_sum / mesh.triangles.size() * px_per_unit;
  // Without edges, a hairline stroke in the fill colour hides the seams that anti-aliasing
  // leaves between neighbouring triangles.
  const bool draw_edges = mean_edge_px >= kMinEdgePx;
  const std::string stroke_width = draw_edges ? "4" : "3";

  std::vector<std::vector<int32_t>> bins(kColourBins);
  for (size_t i = 0; i < quality.size(); ++i) {
    const int bin = std::clamp(static_cast<int>(quality[i] * kColourBins), 0, kColourBins - 1);
    bins[bin].push_back(static_cast<int32_t>(i));
  }
  b.text("<g stroke-linejoin=\"round\" stroke-width=\"").text(stroke_width).text("\">\n");
  for (int k = 0; k < kColourBins; ++k) {
    if (bins[k].empty()) continue;
    const std::string colour = bin_colour(k);
    for (size_t j = 0; j < bins[k].size(); ++j) {
      if (j % kMaxTrianglesPerPath == 0) {
        if (j > 0) b.text("\"/>\n");
        b.text("<path fill=\"").text(colour).text("\" stroke=\"");
        b.text(draw_edges ? "#303030" : colour).text("\" d=\"");
      }
      const auto& t = mesh.triangles[bins[k][j]];
      const auto p0 = to_grid(mesh.points[t[0]]);
      const auto p1 = to_grid(mesh.points[t[1]]);
      const auto p2 = to_grid(mesh.points[t[2]]);
      b.character('M').number(p0[0]).character(' ').number(p0[1]).character('l');
      relative(b, p1[0] - p0[0], p1[1] - p0[1], false);
      relative(b, p2[0] - p1[0], p2[1] - p1[1], true);
      b.character('z');
    }
    b.text("\"/>\n");
  }
  b.text("</g>\n");

  // ---- Boundary, one path per group, chained where edges meet ----
  b.text("<g fill=\"none\" stroke-width=\"25\" stroke-linecap=\"round\" ");
  b.text("stroke-linejoin=\"round\">\n");
  for (size_t g = 0; g < mesh.boundary_names.size(); ++g) {
    b.text("<path stroke=\"").text(kGroupColours[g % kNumGroupColours]).text("\" d=\"");
    int32_t last = -1;
    std::array<int64_t, 2> last_grid{0, 0};
    for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
      if (mesh.boundary_tags[i] != static_cast<int32_t>(g)) continue;
      const auto& e = mesh.boundary_edges[i];
      const bool new_chain = e[0] != last;
      if (new_chain) {
        last_grid = to_grid(mesh.points[e[0]]);
        b.character('M').number(last_grid[0]).character(' ').number(last_grid[1]).character('l');
      }
      const auto next = to_grid(mesh.points[e[1]]);
      relative(b, next[0] - last_grid[0], next[1] - last_grid[1], !new_chain);
      last_grid = next;
      last = e[1];
    }
    b.text("\"/>\n");
  }
  b.text("</g>\n");

  // ---- Legend: colour bar with the quality summary, then the boundary groups ----
  if (options.legend) {
    const double unit = kSubpixels;
    const double row0 = (height_px - legend_px + 4) * unit;
    const double swatch = 8 * unit, x0 = margin_px * unit;
    b.text("<g font-family=\"sans-serif\" font-size=\"").number(12 * kSubpixels).text("\">\n");
    for (int k = 0; k < kColourBins; ++k) {
      b.text("<rect x=\"").number(std::llround(x0 + k * swatch)).text("\" y=\"");
      b.number(std::llround(row0)).text("\" width=\"").number(std::llround(swatch));
      b.text("\" height=\"").number(std::llround(12 * unit)).text("\" fill=\"");
      b.text(bin_colour(k)).text("\"/>\n");
    }
    char summary[160];
    std::snprintf(summary, sizeof(summary),
                  "q = 0 to 1; q_min %.3f, q_mean %.3f, min angle %.1f\u00b0, %zu triangles",
                  stats.q_min, stats.q_mean, stats.min_angle_deg, mesh.triangles.size());
    b.text("<text x=\"").number(std::llround(x0 + (kColourBins + 1) * swatch)).text("\" y=\"");
    b.number(std::llround(row0 + 10.5 * unit)).text("\">").text(summary).text("</text>\n");
    double x = x0;
    const double row1 = row0 + kLegendRowPx * unit;
    for (size_t g = 0; g < mesh.boundary_names.size(); ++g) {
      b.text("<rect x=\"").number(std::llround(x)).text("\" y=\"").number(std::llround(row1));
      b.text("\" width=\"").number(std::llround(14 * unit)).text("\" height=\"");
      b.number(std::llround(12 * unit)).text("\" fill=\"");
      b.text(kGroupColours[g % kNumGroupColours]).text("\"/>\n");
      const std::string name = xml_escaped(mesh.boundary_names[g]);
      b.text("<text x=\"").number(std::llround(x + 18 * unit)).text("\" y=\"");
      b.number(std::llround(row1 + 10.5 * unit)).text("\">").text(name).text("</text>\n");
      // Names are not measured; 7 px per character is a fair guess for 12 px sans-serif.
      x += (18 + 7.0 * mesh.boundary_names[g].size() + 14) * unit;
    }
    b.text("</g>\n");
  }
  b.text("</svg>\n");
}

}  // namespace meshd
