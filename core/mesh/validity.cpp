#include "core/mesh/validity.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/common/error.h"
#include "core/mesh/boundary.h"
#include "core/mesh/boundary_groups_validity.h"

namespace meshd {
namespace {

bool in_range(int32_t index, size_t num_points) {
  return index >= 0 && static_cast<size_t>(index) < num_points;
}

bool triangle_in_range(const std::array<int32_t, 3>& t, size_t num_points) {
  return in_range(t[0], num_points) && in_range(t[1], num_points) && in_range(t[2], num_points);
}

uint64_t directed_key(int32_t a, int32_t b) {
  return (uint64_t{static_cast<uint32_t>(a)} << 32) | static_cast<uint32_t>(b);
}

// ---- Edge use: how many triangles use each edge, and in which directions ---------------------

struct EdgeCounts {
  int64_t interior = 0;
  int64_t nonconforming = 0;
  std::string first_nonconforming;
};

EdgeCounts count_edge_uses(const std::vector<std::array<int32_t, 3>>& triangles) {
  // Half-edges sorted by undirected key; within a group, +1 for a < b and -1 for a > b. A
  // conforming interior edge is a group of two whose directions cancel.
  struct HalfEdge {
    uint64_t key;
    int32_t direction;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      half_edges.push_back({directed_key(std::min(a, b), std::max(a, b)), a < b ? 1 : -1});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key; });

  EdgeCounts counts;
  for (size_t i = 0; i < half_edges.size();) {
    size_t j = i;
    int32_t direction_sum = 0;
    while (j < half_edges.size() && half_edges[j].key == half_edges[i].key) {
      direction_sum += half_edges[j].direction;
      ++j;
    }
    const size_t uses = j - i;
    if (uses == 2 && direction_sum == 0) {
      ++counts.interior;
    } else if (uses >= 2) {
      if (counts.nonconforming++ == 0) {
        std::ostringstream s;
        s << "edge (" << (half_edges[i].key >> 32) << ", " << (half_edges[i].key & 0xffffffffu)
          << ") used by " << uses << " triangles" << (uses == 2 ? " in the same direction" : "");
        counts.first_nonconforming = s.str();
      }
    }
    i = j;
  }
  return counts;
}

// ---- The boundary_edges list against the one-triangle edges ----------------------------------

void check_boundary_list(const Mesh& mesh, const std::vector<std::array<int32_t, 3>>& triangles,
                         ValidityReport& report) {
  const auto topological = boundary_edges_of(triangles);
  report.num_boundary_edges = static_cast<int64_t>(topological.size());

  std::vector<uint64_t> keys;
  keys.reserve(topological.size());
  for (const auto& e : topological) keys.push_back(directed_key(e[0], e[1]));
  std::sort(keys.begin(), keys.end());
  // 1: listed as is, 2: listed reversed (already reported as such, so not also as missing).
  std::vector<char> listed(keys.size(), 0);
  auto find = [&](uint64_t key) -> int64_t {
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    return it != keys.end() && *it == key ? it - keys.begin() : -1;
  };

  std::string first_extra, first_reversed;
  for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
    const auto& e = mesh.boundary_edges[i];
    if (!in_range(e[0], mesh.points.size()) || !in_range(e[1], mesh.points.size())) continue;
    const std::string name = "boundary edge " + std::to_string(i) + " (" + std::to_string(e[0]) +
                             ", " + std::to_string(e[1]) + ")";
    const int64_t k = find(directed_key(e[0], e[1]));
    const int64_t k_reversed = k >= 0 ? -1 : find(directed_key(e[1], e[0]));
    if (k >= 0 && listed[k] == 0) {
      listed[k] = 1;
    } else if (k_reversed >= 0 && listed[k_reversed] == 0) {
      listed[k_reversed] = 2;
      if (report.num_reversed_boundary_edges++ == 0) first_reversed = name;
    } else if (k >= 0 || k_reversed >= 0) {
      if (report.num_extra_boundary_edges++ == 0) first_extra = name + ", listed twice";
    } else {
      if (report.num_extra_boundary_edges++ == 0) first_extra = name;
    }
  }
  std::string first_missing;
  for (size_t k = 0; k < keys.size(); ++k) {
    if (listed[k] != 0) continue;
    if (report.num_missing_boundary_edges++ == 0) {
      first_missing = "edge (" + std::to_string(keys[k] >> 32) + ", " +
                      std::to_string(keys[k] & 0xffffffffu) + ")";
    }
  }
  if (report.num_reversed_boundary_edges > 0) {
    report.problems.push_back(validity_problem(report.num_reversed_boundary_edges,
                                               "boundary edges have the domain on their right",
                                               first_reversed));
  }
  if (report.num_extra_boundary_edges > 0) {
    report.problems.push_back(validity_problem(
        report.num_extra_boundary_edges,
        "listed boundary edges are not used by exactly one triangle", first_extra));
  }
  if (report.num_missing_boundary_edges > 0) {
    report.problems.push_back(validity_problem(
        report.num_missing_boundary_edges,
        "edges used by one triangle are missing from boundary_edges", first_missing));
  }
}

}  // namespace

ValidityReport check_validity(const Mesh& mesh, double area_tolerance) {
  ValidityReport report;
  const size_t num_points = mesh.points.size();
  report.num_points = static_cast<int64_t>(num_points);
  report.num_triangles = static_cast<int64_t>(mesh.triangles.size());

  std::string first;
  for (size_t i = 0; i < num_points; ++i) {
    const Vec2 p = mesh.points[i];
    if (std::isfinite(p.x) && std::isfinite(p.y)) continue;
    if (report.num_nonfinite_points++ == 0) first = "point " + std::to_string(i);
  }
  if (report.num_nonfinite_points > 0) {
    report.problems.push_back(
        validity_problem(report.num_nonfinite_points, "points have non-finite coordinates", first));
  }

  // Triangles with an index out of range take no part in the later checks, which would
  // otherwise read out of bounds; the index problem is reported on its own.
  std::vector<std::array<int32_t, 3>> triangles;
  triangles.reserve(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    if (triangle_in_range(t, num_points)) {
      triangles.push_back(t);
    } else if (report.num_bad_indices++ == 0) {
      first = "triangle " + std::to_string(i) + " (" + std::to_string(t[0]) + ", " +
              std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")";
    }
  }
  for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
    const auto& e = mesh.boundary_edges[i];
    if (in_range(e[0], num_points) && in_range(e[1], num_points)) continue;
    if (report.num_bad_indices++ == 0) {
      first = "boundary edge " + std::to_string(i) + " (" + std::to_string(e[0]) + ", " +
              std::to_string(e[1]) + ")";
    }
  }
  if (report.num_bad_indices > 0) {
    report.problems.push_back(validity_problem(
        report.num_bad_indices,
        "triangles or boundary edges index points outside [0, " + std::to_string(num_points) + ")",
        first));
  }

  // Orientation and area, relative to the longest edge so that the unit does not matter.
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    if (!triangle_in_range(t, num_points)) continue;
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    const double twice_area = cross(b - a, c - a);
    const double longest_sq = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
    // Written so that NaN fails too.
    if (twice_area > area_tolerance * longest_sq) continue;
    if (report.num_inverted++ == 0) {
      report.first_inverted = static_cast<int64_t>(i);
      std::ostringstream s;
      s << "triangle " << i << " (" << t[0] << ", " << t[1] << ", " << t[2]
        << "), 2 area / longest edge^2 = " << twice_area / longest_sq;
      first = s.str();
    }
  }
  if (report.num_inverted > 0) {
    std::ostringstream what;
    what << "triangles are clockwise or degenerate (2 area <= " << area_tolerance
         << " longest edge^2)";
    report.problems.push_back(validity_problem(report.num_inverted, what.str(), first));
  }

  const EdgeCounts edges = count_edge_uses(triangles);
  report.num_interior_edges = edges.interior;
  report.num_nonconforming_edges = edges.nonconforming;
  if (edges.nonconforming > 0) {
    report.problems.push_back(
        validity_problem(edges.nonconforming,
                         "edges are not conforming (used by more than two triangles, "
                         "or by two in the same direction)",
                         edges.first_nonconforming));
  }

  std::vector<char> used(num_points, 0);
  for (const auto& t : triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  for (size_t i = 0; i < num_points; ++i) {
    if (used[i]) continue;
    if (report.num_unused_points++ == 0) first = "point " + std::to_string(i);
  }
  if (report.num_unused_points > 0) {
    report.problems.push_back(
        validity_problem(report.num_unused_points, "points are used by no triangle", first));
  }

  check_boundary_list(mesh, triangles, report);

  const BoundaryGroupDefects groups =
      check_boundary_groups(mesh.boundary_tags, mesh.boundary_edges.size(), mesh.boundary_names,
                            "boundary edges", report.problems);
  report.num_bad_tags = groups.num_bad_tags;
  report.num_bad_names = groups.num_bad_names;
  return report;
}

double mesh_area(const Mesh& mesh) {
  double twice_area = 0.0;
  for (const auto& t : mesh.triangles) {
    if (!triangle_in_range(t, mesh.points.size())) continue;
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    twice_area += cross(b - a, c - a);
  }
  return 0.5 * twice_area;
}

void check_indices(const Mesh& mesh) {
  const size_t num_points = mesh.points.size();
  auto fail = [](const std::string& message) {
    throw Error(ErrorCode::kInternal, "mesh", message);
  };
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (!triangle_in_range(mesh.triangles[i], num_points)) {
      fail("triangle " + std::to_string(i) + " indexes a point outside [0, " +
           std::to_string(num_points) + ")");
    }
  }
  for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
    const auto& e = mesh.boundary_edges[i];
    if (!in_range(e[0], num_points) || !in_range(e[1], num_points)) {
      fail("boundary edge " + std::to_string(i) + " indexes a point outside [0, " +
           std::to_string(num_points) + ")");
    }
  }
  const std::string tags = boundary_tags_problem(mesh.boundary_tags, mesh.boundary_edges.size(),
                                                 mesh.boundary_names.size(), "boundary edges");
  if (!tags.empty()) fail(tags);
}

}  // namespace meshd
