#include "core/geometry3d/triangle_surface3.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <unordered_map>
#include <utility>

#include "core/common/error.h"
#include "core/geometry3d/surface_self_intersection3.h"

namespace meshd {
namespace {

// Triangles per leaf of the hierarchy.
constexpr size_t kLeafTriangles = 4;

uint64_t edge_key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

Vec3 unit(Vec3 v) {
  const double n = norm(v);
  return n > 0.0 ? (1.0 / n) * v : Vec3{};
}

Box3 grow(Box3 b, Vec3 p) {
  return {{std::min(b.min.x, p.x), std::min(b.min.y, p.y), std::min(b.min.z, p.z)},
          {std::max(b.max.x, p.x), std::max(b.max.y, p.y), std::max(b.max.z, p.z)}};
}

constexpr Box3 kEmptyBox{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};

std::string edge_text(int32_t a, int32_t b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

// Median splits along the widest axis of the triangles' centres, over `order` (triangle
// indices), which ends up in tree order.
class TreeBuilder {
 public:
  TreeBuilder(const std::vector<Box3>& boxes, std::vector<uint32_t>& order,
              std::vector<SurfaceBvhNode>& nodes)
      : boxes_(boxes), order_(order), nodes_(nodes) {}

  uint32_t build(size_t begin, size_t end) {
    Box3 box = kEmptyBox, centres = kEmptyBox;
    for (size_t i = begin; i < end; ++i) {
      const Box3& b = boxes_[order_[i]];
      box = grow(grow(box, b.min), b.max);
      centres = grow(centres, 0.5 * (b.min + b.max));
    }
    const auto index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({box, static_cast<uint32_t>(begin), static_cast<uint32_t>(end), 1});
    if (end - begin <= kLeafTriangles) return index;
    const Vec3 extent = centres.max - centres.min;
    const int axis =
        extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const auto centre = [&](uint32_t t) {
      const Box3& b = boxes_[t];
      return axis == 0 ? b.min.x + b.max.x : axis == 1 ? b.min.y + b.max.y : b.min.z + b.max.z;
    };
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                     order_.begin() + static_cast<std::ptrdiff_t>(mid),
                     order_.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](uint32_t a, uint32_t b) {
                       return centre(a) < centre(b) || (centre(a) == centre(b) && a < b);
                     });
    const uint32_t left = build(begin, mid);
    const uint32_t right = build(mid, end);
    nodes_[index].first = left;
    nodes_[index].last = right;
    nodes_[index].leaf = 0;
    return index;
  }

 private:
  const std::vector<Box3>& boxes_;
  std::vector<uint32_t>& order_;
  std::vector<SurfaceBvhNode>& nodes_;
};

}  // namespace

TriangleSurface3 build_triangle_surface3(std::vector<Vec3> vertices,
                                         const std::vector<std::array<int32_t, 3>>& input,
                                         const std::string& path) {
  const std::string tri_field = path + ".triangles";
  if (input.size() < 4) {
    throw_invalid(tri_field, "a closed surface needs at least 4 triangles (got " +
                                 std::to_string(input.size()) + ")");
  }
  const auto n_vertices = static_cast<int64_t>(vertices.size());
  std::vector<std::array<int32_t, 3>> tris = input;
  for (size_t t = 0; t < tris.size(); ++t) {
    for (int32_t v : tris[t])
      if (v < 0 || v >= n_vertices) {
        throw_invalid(tri_field, "triangle " + std::to_string(t) + " uses vertex " +
                                     std::to_string(v) + ", outside [0, " +
                                     std::to_string(n_vertices) + ")");
      }
    const Vec3 a = vertices[tris[t][0]], b = vertices[tris[t][1]], c = vertices[tris[t][2]];
    if (!(norm(cross(b - a, c - a)) > 0.0))
      throw_invalid(tri_field, "triangle " + std::to_string(t) + " has zero area");
  }

  // Every directed edge once, and its reverse once: closed, manifold, consistently oriented.
  std::unordered_map<uint64_t, int32_t> edge_triangle;
  edge_triangle.reserve(3 * tris.size());
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
      if (!edge_triangle.emplace(edge_key(a, b), static_cast<int32_t>(t)).second) {
        throw_invalid(
            tri_field,
            "edge " + edge_text(a, b) + " is used twice in the same direction (by triangles " +
                std::to_string(edge_triangle[edge_key(a, b)]) + " and " + std::to_string(t) +
                "): the surface is not manifold, or its triangles are not all turned the same way");
      }
    }
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
      if (!edge_triangle.contains(edge_key(b, a))) {
        throw_invalid(tri_field,
                      "edge " + edge_text(a, b) + " of triangle " + std::to_string(t) +
                          " has no triangle on its other side: the surface must be closed");
      }
    }

  if (const auto crossing = find_surface_self_intersection3(vertices, tris)) {
    throw_invalid(tri_field, "triangles " + std::to_string((*crossing)[0]) + " and " +
                                 std::to_string((*crossing)[1]) +
                                 " cross: the surface intersects itself, so it has no inside");
  }

  // Outward: a surface given inward encloses a negative volume.
  double volume6 = 0.0;
  for (const auto& t : tris) volume6 += dot(vertices[t[0]], cross(vertices[t[1]], vertices[t[2]]));
  if (!(std::fabs(volume6) > 0.0) || !std::isfinite(volume6))
    throw_invalid(tri_field, "the surface encloses no volume");
  const bool inward = volume6 < 0.0;
  if (inward)
    for (auto& t : tris) std::swap(t[1], t[2]);

  TriangleSurface3 out;
  // Face normals, vertex pseudonormals (each face's normal weighted by its angle there).
  std::vector<Vec3> face(tris.size());
  out.vertex_normals.assign(vertices.size(), Vec3{});
  out.box = kEmptyBox;
  std::vector<Box3> boxes(tris.size(), kEmptyBox);
  for (size_t t = 0; t < tris.size(); ++t) {
    const Vec3 p[3] = {vertices[tris[t][0]], vertices[tris[t][1]], vertices[tris[t][2]]};
    face[t] = unit(cross(p[1] - p[0], p[2] - p[0]));
    for (int k = 0; k < 3; ++k) {
      const Vec3 e1 = unit(p[(k + 1) % 3] - p[k]), e2 = unit(p[(k + 2) % 3] - p[k]);
      const double angle = std::acos(std::clamp(dot(e1, e2), -1.0, 1.0));
      out.vertex_normals[tris[t][k]] = out.vertex_normals[tris[t][k]] + angle * face[t];
      boxes[t] = grow(boxes[t], p[k]);
    }
    out.box = grow(grow(out.box, boxes[t].min), boxes[t].max);
  }
  // After a turn the map's keys are reversed: look edges up in the orientation they were given.
  const auto neighbour = [&](int32_t a, int32_t b) {
    return inward ? edge_triangle.at(edge_key(a, b)) : edge_triangle.at(edge_key(b, a));
  };
  const double sharp_cos = std::cos(kSharpSurfaceAngleDeg * std::numbers::pi / 180.0);
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
      if (a < b && dot(face[t], face[neighbour(a, b)]) < sharp_cos)
        out.sharp_edges.push_back({a, b});
    }

  // The tree, and the triangles with their normals in its order.
  std::vector<uint32_t> order(tris.size());
  std::iota(order.begin(), order.end(), 0u);
  out.root = TreeBuilder(boxes, order, out.nodes).build(0, tris.size());
  out.triangles.reserve(3 * tris.size());
  out.triangle_normals.reserve(4 * tris.size());
  for (uint32_t t : order) {
    out.triangle_normals.push_back(face[t]);
    for (int k = 0; k < 3; ++k) {
      const int32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
      out.triangles.push_back(a);
      out.triangle_normals.push_back(face[t] + face[neighbour(a, b)]);
    }
  }
  out.vertices = std::move(vertices);
  return out;
}

}  // namespace meshd
