#include "core/distmesh/assemble_mesh.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/boundary.h"

namespace meshd {

namespace {

// Drops the points no triangle uses and turns clockwise triangles over; returns the boundary
// half-edges' ids in the new triangles.
std::vector<int32_t> renumber_and_orient(Mesh& mesh, const std::vector<Vec2>& points,
                                         const std::vector<std::array<int32_t, 3>>& triangles,
                                         const std::vector<int32_t>& boundary) {
  std::vector<int32_t> new_index(points.size(), -1);
  for (const auto& t : triangles)
    for (int32_t v : t) new_index[v] = 0;
  int32_t used = 0;
  for (int32_t& k : new_index)
    if (k == 0) k = used++;
  mesh.points.reserve(static_cast<size_t>(used));
  for (size_t i = 0; i < points.size(); ++i)
    if (new_index[i] >= 0) mesh.points.push_back(points[i]);
  std::vector<int32_t> turned;  // triangles turned over, increasing
  mesh.triangles.reserve(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    std::array<int32_t, 3> u{new_index[triangles[t][0]], new_index[triangles[t][1]],
                             new_index[triangles[t][2]]};
    const Vec2 a = mesh.points[u[0]], b = mesh.points[u[1]], c = mesh.points[u[2]];
    if (cross(b - a, c - a) < 0.0) {
      std::swap(u[1], u[2]);
      turned.push_back(static_cast<int32_t>(t));
    }
    mesh.triangles.push_back(u);
  }

  // Turning a triangle over reverses its half-edges and their order: boundary half-edge
  // 3 t + k becomes 3 t + 2 - k (boundary.h).
  std::vector<int32_t> ids(boundary);
  if (!turned.empty()) {
    for (int32_t& id : ids)
      if (std::binary_search(turned.begin(), turned.end(), id / 3)) id = 3 * (id / 3) + 2 - id % 3;
    std::sort(ids.begin(), ids.end());
  }
  return ids;
}

}  // namespace

Mesh assemble_mesh(const CompiledProblem& problem, std::vector<Vec2> points,
                   std::vector<std::array<int32_t, 3>> triangles,
                   const std::vector<int32_t>& boundary, bool tidy) {
  Mesh mesh;
  if (tidy) {
    mesh.points = std::move(points);
    mesh.triangles = std::move(triangles);
    mesh.boundary_edges = half_edge_ends(mesh.triangles, boundary);
  } else {
    const std::vector<int32_t> ids = renumber_and_orient(mesh, points, triangles, boundary);
    mesh.boundary_edges = half_edge_ends(mesh.triangles, ids);
  }
  // The primitive that wins the min / max at an edge's midpoint is the boundary it lies on.
  std::map<std::string, int32_t> group_of_name;
  std::vector<int32_t> group_of_primitive(problem.geometry.primitives.size(), -1);
  std::vector<int32_t> owner_tag(problem.geometry.primitives.size(), -1);
  mesh.boundary_tags.reserve(mesh.boundary_edges.size());
  for (const auto& e : mesh.boundary_edges) {
    const Vec2 mid = 0.5 * (mesh.points[e[0]] + mesh.points[e[1]]);
    int owner = 0;
    eval_sdf_range(problem.geometry.view(), 0, static_cast<uint32_t>(problem.geometry.code.size()),
                   mid, &owner);
    owner_tag[owner] = 0;
    mesh.boundary_tags.push_back(owner);
  }
  // Number groups in primitive order so that tags do not depend on the edge order.
  for (size_t prim = 0; prim < owner_tag.size(); ++prim) {
    if (owner_tag[prim] < 0) continue;
    const std::string& name = problem.geometry.primitives[prim].name;
    auto [it, inserted] =
        group_of_name.emplace(name, static_cast<int32_t>(mesh.boundary_names.size()));
    if (inserted) mesh.boundary_names.push_back(name);
    group_of_primitive[prim] = it->second;
  }
  for (int32_t& tag : mesh.boundary_tags) tag = group_of_primitive[tag];
  return mesh;
}

}  // namespace meshd
