#include "core/geometry3d/surface_self_intersection3.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <utility>

namespace meshd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = Mesh::Face_index;
namespace pmp = CGAL::Polygon_mesh_processing;

// Keeps the first pair it is given and stops the search there.
struct FirstPair {
  struct Found {};
  std::pair<Face, Face>* first;
  FirstPair& operator*() { return *this; }
  FirstPair& operator++() { return *this; }
  FirstPair operator++(int) { return *this; }
  FirstPair& operator=(const std::pair<Face, Face>& pair) {
    *first = pair;
    throw Found{};
  }
};

// The surface as CGAL's mesh, face i triangle i; false where a vertex joins separate fans of
// triangles, which a halfedge mesh cannot hold as one vertex.
bool direct_mesh(const std::vector<Vec3>& vertices,
                 const std::vector<std::array<int32_t, 3>>& triangles, Mesh& mesh) {
  mesh.reserve(vertices.size(), 3 * triangles.size() / 2, triangles.size());
  for (const Vec3& v : vertices) mesh.add_vertex(Kernel::Point_3(v.x, v.y, v.z));
  for (const auto& t : triangles) {
    const Face f =
        mesh.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
    if (f == Mesh::null_face()) {
      mesh.clear();
      return false;
    }
  }
  return true;
}

// The same through CGAL's polygon soup repair, which gives a vertex where separate fans meet one
// copy per fan (at the same place), so that the fans' triangles touch there rather than share
// it. The triangles keep their order (and their orientation, consistent already).
void soup_mesh(const std::vector<Vec3>& vertices,
               const std::vector<std::array<int32_t, 3>>& triangles, Mesh& mesh) {
  std::vector<Kernel::Point_3> points;
  points.reserve(vertices.size());
  for (const Vec3& v : vertices) points.emplace_back(v.x, v.y, v.z);
  std::vector<std::array<size_t, 3>> faces;
  faces.reserve(triangles.size());
  for (const auto& t : triangles)
    faces.push_back(
        {static_cast<size_t>(t[0]), static_cast<size_t>(t[1]), static_cast<size_t>(t[2])});
  pmp::orient_polygon_soup(points, faces);
  pmp::polygon_soup_to_polygon_mesh(points, faces, mesh);
}

}  // namespace

std::optional<std::array<int32_t, 2>> find_surface_self_intersection3(
    const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 3>>& triangles) {
  Mesh mesh;
  if (!direct_mesh(vertices, triangles, mesh)) soup_mesh(vertices, triangles, mesh);
  if (!pmp::does_self_intersect<CGAL::Parallel_if_available_tag>(mesh)) return std::nullopt;
  std::pair<Face, Face> pair;
  try {
    pmp::self_intersections(mesh, FirstPair{&pair});
    return std::nullopt;  // not reached: the parallel search found a pair
  } catch (const FirstPair::Found&) {
  }
  const auto a = static_cast<int32_t>(pair.first.idx());
  const auto b = static_cast<int32_t>(pair.second.idx());
  return std::array<int32_t, 2>{std::min(a, b), std::max(a, b)};
}

}  // namespace meshd
