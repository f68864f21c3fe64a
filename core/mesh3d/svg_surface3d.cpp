#include "core/mesh3d/svg_surface3d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/quality_colours.h"
#include "core/mesh3d/tet_quality.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// The view: towards the viewer along `eye`, the screen's x and y axes `right` and `up`; the light
// comes from over the viewer's left shoulder.
struct View {
  Vec3 eye, right, up, light;
};

Vec3 unit(Vec3 v) { return (1.0 / norm(v)) * v; }

View default_view() {
  View v;
  v.eye = unit({1.0, -1.6, 1.1});
  v.right = unit(cross({0, 0, 1}, v.eye));
  v.up = cross(v.eye, v.right);
  v.light = unit(v.eye + 0.6 * v.up - 0.5 * v.right);
  return v;
}

// The tetrahedron each boundary face belongs to, by its sorted corners.
std::vector<int64_t> face_owners(const TetMesh& mesh) {
  std::map<std::array<int32_t, 3>, int64_t> index;
  for (size_t f = 0; f < mesh.boundary_faces.size(); ++f) {
    auto key = mesh.boundary_faces[f];
    std::sort(key.begin(), key.end());
    index.emplace(key, static_cast<int64_t>(f));
  }
  std::vector<int64_t> owner(mesh.boundary_faces.size(), -1);
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (const auto& f : kFace) {
      std::array<int32_t, 3> key{mesh.tets[t][f[0]], mesh.tets[t][f[1]], mesh.tets[t][f[2]]};
      std::sort(key.begin(), key.end());
      const auto it = index.find(key);
      if (it != index.end()) owner[it->second] = static_cast<int64_t>(t);
    }
  return owner;
}

}  // namespace

void write_svg_surface3d(const TetMesh& mesh, std::ostream& out, const SvgSurfaceOptions& options) {
  check_indices(mesh);
  const View view = default_view();
  const std::vector<double> q = tet_quality(mesh);
  const std::vector<int64_t> owner = face_owners(mesh);

  // The faces that face the viewer, far ones first.
  struct Face {
    double depth;
    size_t index;
  };
  std::vector<Face> faces;
  double min_x = INFINITY, max_x = -INFINITY, min_y = INFINITY, max_y = -INFINITY;
  for (const Vec3& p : mesh.points) {
    min_x = std::min(min_x, dot(p, view.right));
    max_x = std::max(max_x, dot(p, view.right));
    min_y = std::min(min_y, dot(p, view.up));
    max_y = std::max(max_y, dot(p, view.up));
  }
  for (size_t f = 0; f < mesh.boundary_faces.size(); ++f) {
    const auto& v = mesh.boundary_faces[f];
    const Vec3 a = mesh.points[v[0]], b = mesh.points[v[1]], c = mesh.points[v[2]];
    if (dot(cross(b - a, c - a), view.eye) <= 0.0) continue;
    faces.push_back({dot(a + b + c, view.eye), f});
  }
  std::sort(faces.begin(), faces.end(),
            [](const Face& x, const Face& y) { return x.depth < y.depth; });

  const double width = options.width_px, margin = options.margin * width;
  const double span_x = std::max(max_x - min_x, 1e-300), span_y = std::max(max_y - min_y, 0.0);
  const double scale = mesh.points.empty() ? 1.0 : (width - 2 * margin) / span_x;
  const double legend = 26;
  const double height = std::ceil(span_y * scale + 2 * margin + legend);
  char line[512];
  std::snprintf(line, sizeof line,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
                "viewBox=\"0 0 %d %d\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                options.width_px, static_cast<int>(height), options.width_px,
                static_cast<int>(height));
  out << line;
  // Face edges only where faces are large enough on the page for them to be seen.
  const double mean_edge =
      mesh.points.empty() ? 0.0 : scale * span_x / std::sqrt(std::max<size_t>(faces.size(), 1));
  out << "<g stroke-linejoin=\"round\""
      << (mean_edge >= 6 ? " stroke=\"#303030\" stroke-width=\"0.3\"" : "") << ">\n";
  for (const Face& face : faces) {
    const auto& v = mesh.boundary_faces[face.index];
    const Vec3 a = mesh.points[v[0]], b = mesh.points[v[1]], c = mesh.points[v[2]];
    const double lit = 0.45 + 0.55 * std::fabs(dot(unit(cross(b - a, c - a)), view.light));
    const int64_t t = owner[face.index];
    const Rgb base = quality_colour(t >= 0 ? q[t] : 0.0);
    const std::string fill = hex({base.r * lit, base.g * lit, base.b * lit});
    const auto x = [&](Vec3 p) { return margin + (dot(p, view.right) - min_x) * scale; };
    const auto y = [&](Vec3 p) { return margin + (max_y - dot(p, view.up)) * scale; };
    std::snprintf(line, sizeof line,
                  "<path d=\"M%.1f %.1fL%.1f %.1fL%.1f %.1fZ\" fill=\"%s\"%s/>\n", x(a), y(a), x(b),
                  y(b), x(c), y(c), fill.c_str(),
                  mean_edge >= 6 ? "" : (" stroke=\"" + fill + "\" stroke-width=\"0.4\"").c_str());
    out << line;
  }
  out << "</g>\n";
  const TetQualityStats stats = summarize_tet_quality(mesh);
  std::snprintf(line, sizeof line,
                "<text x=\"%.0f\" y=\"%.0f\" font-family=\"sans-serif\" font-size=\"13\">%zu "
                "nodes, %zu tetrahedra; q_min %.3f, q_mean %.3f; dihedral %.1f-%.1f deg (fill: "
                "q of the face's tetrahedron, red 0 to blue 1)</text>\n",
                margin, height - 9, mesh.points.size(), mesh.tets.size(), stats.q_min, stats.q_mean,
                stats.min_dihedral_deg, stats.max_dihedral_deg);
  out << line << "</svg>\n";
}

}  // namespace meshd
