#include "core/delaunay/delaunay.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <utility>

namespace meshd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int32_t, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<int32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
// Crossing constraints throw instead of being split at a constructed intersection point.
using ConstrainedFaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBase>;
using ConstrainedTds = CGAL::Triangulation_data_structure_2<VertexBase, ConstrainedFaceBase>;
using ConstrainedDelaunay =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, ConstrainedTds,
                                               CGAL::No_constraint_intersection_tag>;

std::vector<std::pair<Kernel::Point_2, int32_t>> with_indices(const std::vector<Vec2>& points) {
  std::vector<std::pair<Kernel::Point_2, int32_t>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_2(points[i].x, points[i].y), static_cast<int32_t>(i));
  return input;
}

// The finite faces of `dt` as arrays; overwrites the faces' info.
template <typename Dt>
Triangulation to_arrays(Dt& dt) {
  Triangulation out;
  out.triangles.reserve(dt.number_of_faces());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    f->info() = static_cast<int32_t>(out.triangles.size());
    out.triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
    if (dt.is_infinite(f)) f->info() = -1;
  out.neighbors.reserve(out.triangles.size());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    out.neighbors.push_back(
        {f->neighbor(0)->info(), f->neighbor(1)->info(), f->neighbor(2)->info()});
  return out;
}

}  // namespace

Triangulation delaunay_triangulate(const std::vector<Vec2>& points) {
  const auto input = with_indices(points);
  Delaunay dt;
  dt.insert(input.begin(), input.end());  // spatially sorted insertion
  return to_arrays(dt);
}

Triangulation constrained_delaunay_triangulate(
    const std::vector<Vec2>& points, const std::vector<std::array<int32_t, 2>>& constraints) {
  const auto input = with_indices(points);
  ConstrainedDelaunay cdt;
  cdt.insert(input.begin(), input.end());
  std::vector<ConstrainedDelaunay::Vertex_handle> vertex(points.size());
  std::vector<char> has_vertex(points.size(), 0);
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    vertex[v->info()] = v;
    has_vertex[v->info()] = 1;
  }
  try {
    for (const auto& c : constraints) {
      // An end that coincides with another point has no vertex of its own.
      if (!has_vertex[c[0]] || !has_vertex[c[1]]) return {};
      cdt.insert_constraint(vertex[c[0]], vertex[c[1]]);
    }
  } catch (const ConstrainedDelaunay::Intersection_of_constraints_exception&) {
    return {};
  }
  return to_arrays(cdt);
}

}  // namespace meshd

namespace meshd {

void drop_triangles(Triangulation& tri, const std::vector<char>& drop) {
  std::vector<int32_t> new_index(tri.triangles.size(), -1);
  int32_t next = 0;
  for (size_t t = 0; t < tri.triangles.size(); ++t)
    if (!drop[t]) new_index[t] = next++;
  for (size_t t = 0; t < tri.triangles.size(); ++t) {
    if (drop[t]) continue;
    tri.triangles[new_index[t]] = tri.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int32_t u = tri.neighbors[t][k];
      tri.neighbors[new_index[t]][k] = u < 0 ? -1 : new_index[u];
    }
  }
  tri.triangles.resize(next);
  tri.neighbors.resize(next);
}

std::vector<std::array<int32_t, 2>> edges_of_kept(const Triangulation& tri,
                                                  const std::vector<char>& keep) {
  std::vector<std::array<int32_t, 2>> edges;
  edges.reserve(2 * tri.triangles.size());
  for (size_t t = 0; t < tri.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int32_t u = tri.neighbors[t][k];
      // Each interior edge once, from its lower-numbered triangle.
      if (u >= 0 && u < static_cast<int32_t>(t)) continue;
      if (!keep[t] && (u < 0 || !keep[u])) continue;
      edges.push_back({tri.triangles[t][(k + 1) % 3], tri.triangles[t][(k + 2) % 3]});
    }
  }
  return edges;
}

}  // namespace meshd
