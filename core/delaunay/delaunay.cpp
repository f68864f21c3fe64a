#include "core/delaunay/delaunay.h"

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

}  // namespace

Triangulation delaunay_triangulate(const std::vector<Vec2>& points) {
  std::vector<std::pair<Kernel::Point_2, int32_t>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_2(points[i].x, points[i].y), static_cast<int32_t>(i));
  Delaunay dt;
  dt.insert(input.begin(), input.end());  // spatially sorted insertion

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

}  // namespace meshd

namespace meshd {

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
