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

  const size_t n_edges = dt.number_of_vertices() + out.triangles.size() + 1;  // Euler, roughly
  out.edges.reserve(n_edges);
  out.edge_faces.reserve(n_edges);
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    out.edges.push_back({f->vertex(Delaunay::cw(i))->info(), f->vertex(Delaunay::ccw(i))->info()});
    out.edge_faces.push_back({f->info(), f->neighbor(i)->info()});
  }
  return out;
}

}  // namespace meshd
