#include "core/delaunay/delaunay3d.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <unordered_map>
#include <utility>

namespace meshd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

// CGAL keeps one vertex for points that coincide, whichever its insertion order met first:
// renumber the tetrahedra to the lowest index of each such set, so that a fixed node (the lowest
// indices) keeps its place when a free node lands on it.
void use_lowest_duplicates(const std::vector<Vec3>& points,
                           std::vector<std::array<int32_t, 4>>& tets) {
  struct Hash {
    size_t operator()(const Vec3& p) const {
      const auto h = [](double v) { return std::hash<double>()(v); };
      return h(p.x) ^ (h(p.y) * 0x9E3779B97F4A7C15ull) ^ (h(p.z) * 0xBF58476D1CE4E5B9ull);
    }
  };
  struct Equal {
    bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
  };
  std::unordered_map<Vec3, int32_t, Hash, Equal> lowest;
  lowest.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) lowest.emplace(points[i], static_cast<int32_t>(i));
  for (auto& t : tets)
    for (int32_t& v : t) v = lowest.at(points[v]);
}

}  // namespace

std::vector<std::array<int32_t, 4>> delaunay_tetrahedralize(const std::vector<Vec3>& points) {
  std::vector<std::pair<Kernel::Point_3, int32_t>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x, points[i].y, points[i].z),
                       static_cast<int32_t>(i));
  Delaunay dt;
  dt.insert(input.begin(), input.end());  // spatially sorted insertion
  std::vector<std::array<int32_t, 4>> tets;
  tets.reserve(dt.number_of_finite_cells());
  // CGAL orders each cell's vertices positively, the convention promised above.
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    tets.push_back(
        {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  if (dt.number_of_vertices() < points.size()) use_lowest_duplicates(points, tets);
  return tets;
}

}  // namespace meshd
