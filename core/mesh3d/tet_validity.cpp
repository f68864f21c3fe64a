#include "core/mesh3d/tet_validity.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "core/common/error.h"
#include "core/mesh/boundary_groups_validity.h"
#include "core/mesh3d/tet_boundary.h"

namespace meshd {
namespace {

using Face = std::array<int32_t, 3>;
using Tet = std::array<int32_t, 4>;

bool in_range(int32_t index, size_t num_points) {
  return index >= 0 && static_cast<size_t>(index) < num_points;
}

template <size_t K>
bool all_in_range(const std::array<int32_t, K>& corners, size_t num_points) {
  return std::all_of(corners.begin(), corners.end(),
                     [&](int32_t v) { return in_range(v, num_points); });
}

// "(a, b, c)" or "(a, b, c, d)".
template <size_t K>
std::string corners_text(const std::array<int32_t, K>& corners) {
  std::string s = "(";
  for (size_t i = 0; i < K; ++i) s += (i > 0 ? ", " : "") + std::to_string(corners[i]);
  return s + ")";
}

// A face's corners rotated so that the smallest comes first: one triple for every listing of the
// face in the same turn, and another for the opposite turn.
Face rotated(const Face& f) {
  if (f[1] < f[0] && f[1] < f[2]) return {f[1], f[2], f[0]};
  if (f[2] < f[0] && f[2] < f[1]) return {f[2], f[0], f[1]};
  return f;
}

Face reversed(const Face& f) { return {f[0], f[2], f[1]}; }

// ---- Face use: how many tetrahedra have each face, and in which turns -------------------------

struct FaceCounts {
  int64_t interior = 0;
  int64_t nonconforming = 0;
  std::string first_nonconforming;
  std::vector<Face> once;  // the faces used once, turned as their tetrahedron has them, rotated
};

FaceCounts count_face_uses(const std::vector<Tet>& tets) {
  // Each face as its sorted corners and whether the tetrahedron turns it that way (rotated, it
  // is (s0, s1, s2) or (s0, s2, s1)), sorted: a face is a run of equal corners, and a conforming
  // interior face is a run of two with opposite turns.
  struct Use {
    Face sorted;
    int32_t as_sorted;
  };
  std::vector<Use> uses;
  uses.reserve(4 * tets.size());
  for (const Tet& t : tets) {
    for (int k = 0; k < 4; ++k) {
      const Face r = rotated(tet_face(t, k));
      uses.push_back({{r[0], std::min(r[1], r[2]), std::max(r[1], r[2])}, r[1] < r[2]});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.sorted < y.sorted || (x.sorted == y.sorted && x.as_sorted < y.as_sorted);
  });

  FaceCounts counts;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].sorted == uses[i].sorted) ++j;
    const size_t n = j - i;
    const Face& s = uses[i].sorted;
    if (n == 1) {
      counts.once.push_back(uses[i].as_sorted ? s : reversed(s));
    } else if (n == 2 && uses[i].as_sorted != uses[i + 1].as_sorted) {
      ++counts.interior;
    } else if (counts.nonconforming++ == 0) {
      counts.first_nonconforming = "face " + corners_text(s) + " used by " + std::to_string(n) +
                                   " tetrahedra" + (n == 2 ? " in the same turn" : "");
    }
    i = j;
  }
  return counts;
}

// ---- The boundary_faces list against the one-tetrahedron faces --------------------------------

void check_boundary_list(const TetMesh& mesh, std::vector<Face> once, TetValidityReport& report) {
  report.num_boundary_faces = static_cast<int64_t>(once.size());
  std::sort(once.begin(), once.end());
  // 1: listed as is, 2: listed reversed (already reported as such, so not also as missing).
  std::vector<char> listed(once.size(), 0);
  auto find = [&](const Face& key) -> int64_t {
    const auto it = std::lower_bound(once.begin(), once.end(), key);
    return it != once.end() && *it == key ? it - once.begin() : -1;
  };

  std::string first_extra, first_reversed;
  for (size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    const Face& f = mesh.boundary_faces[i];
    if (!all_in_range(f, mesh.points.size())) continue;
    const std::string name = "boundary face " + std::to_string(i) + " " + corners_text(f);
    const int64_t k = find(rotated(f));
    const int64_t k_reversed = k >= 0 ? -1 : find(rotated(reversed(f)));
    if (k >= 0 && listed[k] == 0) {
      listed[k] = 1;
    } else if (k_reversed >= 0 && listed[k_reversed] == 0) {
      listed[k_reversed] = 2;
      if (report.num_reversed_boundary_faces++ == 0) first_reversed = name;
    } else if (k >= 0 || k_reversed >= 0) {
      if (report.num_extra_boundary_faces++ == 0) first_extra = name + ", listed twice";
    } else {
      if (report.num_extra_boundary_faces++ == 0) first_extra = name;
    }
  }
  std::string first_missing;
  for (size_t k = 0; k < once.size(); ++k) {
    if (listed[k] != 0) continue;
    if (report.num_missing_boundary_faces++ == 0) first_missing = "face " + corners_text(once[k]);
  }
  if (report.num_reversed_boundary_faces > 0) {
    report.problems.push_back(validity_problem(
        report.num_reversed_boundary_faces,
        "boundary faces are turned inward (their normal points into the domain)", first_reversed));
  }
  if (report.num_extra_boundary_faces > 0) {
    report.problems.push_back(validity_problem(
        report.num_extra_boundary_faces,
        "listed boundary faces are not used by exactly one tetrahedron", first_extra));
  }
  if (report.num_missing_boundary_faces > 0) {
    report.problems.push_back(validity_problem(
        report.num_missing_boundary_faces,
        "faces used by one tetrahedron are missing from boundary_faces", first_missing));
  }
}

// 6 V of the tetrahedron abcd, as orient3d has it.
double six_volume(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return dot(b - a, cross(c - a, d - a)); }

double six_volume(const TetMesh& mesh, const Tet& t) {
  const auto& p = mesh.points;
  return six_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
}

}  // namespace

double relative_six_volume(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 corners[4] = {a, b, c, d};
  double longest_sq = 0.0;
  for (int j = 0; j < 4; ++j) {
    for (int k = j + 1; k < 4; ++k) {
      const Vec3 e = corners[k] - corners[j];
      longest_sq = std::max(longest_sq, dot(e, e));
    }
  }
  return six_volume(a, b, c, d) / (longest_sq * std::sqrt(longest_sq));
}

TetValidityReport check_tet_validity(const TetMesh& mesh, double volume_tolerance) {
  TetValidityReport report;
  const size_t num_points = mesh.points.size();
  report.num_points = static_cast<int64_t>(num_points);
  report.num_tets = static_cast<int64_t>(mesh.tets.size());

  std::string first;
  for (size_t i = 0; i < num_points; ++i) {
    const Vec3 p = mesh.points[i];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
    if (report.num_nonfinite_points++ == 0) first = "point " + std::to_string(i);
  }
  if (report.num_nonfinite_points > 0) {
    report.problems.push_back(
        validity_problem(report.num_nonfinite_points, "points have non-finite coordinates", first));
  }

  // Tetrahedra with an index out of range take no part in the later checks, which would
  // otherwise read out of bounds; the index problem is reported on its own.
  std::vector<Tet> tets;
  tets.reserve(mesh.tets.size());
  for (size_t i = 0; i < mesh.tets.size(); ++i) {
    const Tet& t = mesh.tets[i];
    if (all_in_range(t, num_points)) {
      tets.push_back(t);
    } else if (report.num_bad_indices++ == 0) {
      first = "tetrahedron " + std::to_string(i) + " " + corners_text(t);
    }
  }
  for (size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    const Face& f = mesh.boundary_faces[i];
    if (all_in_range(f, num_points)) continue;
    if (report.num_bad_indices++ == 0) {
      first = "boundary face " + std::to_string(i) + " " + corners_text(f);
    }
  }
  if (report.num_bad_indices > 0) {
    report.problems.push_back(validity_problem(report.num_bad_indices,
                                               "tetrahedra or boundary faces index points outside "
                                               "[0, " +
                                                   std::to_string(num_points) + ")",
                                               first));
  }

  // Orientation and volume, relative to the longest edge so that the unit does not matter.
  for (size_t i = 0; i < mesh.tets.size(); ++i) {
    const Tet& t = mesh.tets[i];
    if (!all_in_range(t, num_points)) continue;
    const auto& p = mesh.points;
    if (!degenerate_tet(p[t[0]], p[t[1]], p[t[2]], p[t[3]], volume_tolerance)) continue;
    if (report.num_inverted++ == 0) {
      report.first_inverted = static_cast<int64_t>(i);
      std::ostringstream s;
      s << "tetrahedron " << i << " " << corners_text(t) << ", 6 volume / longest edge^3 = "
        << relative_six_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
      first = s.str();
    }
  }
  if (report.num_inverted > 0) {
    std::ostringstream what;
    what << "tetrahedra are negatively oriented or degenerate (6 volume <= " << volume_tolerance
         << " longest edge^3)";
    report.problems.push_back(validity_problem(report.num_inverted, what.str(), first));
  }

  FaceCounts faces = count_face_uses(tets);
  report.num_interior_faces = faces.interior;
  report.num_nonconforming_faces = faces.nonconforming;
  if (faces.nonconforming > 0) {
    report.problems.push_back(
        validity_problem(faces.nonconforming,
                         "faces are not conforming (used by more than two tetrahedra, or by two "
                         "in the same turn)",
                         faces.first_nonconforming));
  }

  std::vector<char> used(num_points, 0);
  for (const Tet& t : tets)
    for (const int32_t v : t) used[v] = 1;
  for (size_t i = 0; i < num_points; ++i) {
    if (used[i]) continue;
    if (report.num_unused_points++ == 0) first = "point " + std::to_string(i);
  }
  if (report.num_unused_points > 0) {
    report.problems.push_back(
        validity_problem(report.num_unused_points, "points are used by no tetrahedron", first));
  }

  check_boundary_list(mesh, std::move(faces.once), report);

  const BoundaryGroupDefects groups =
      check_boundary_groups(mesh.boundary_tags, mesh.boundary_faces.size(), mesh.boundary_names,
                            "boundary faces", report.problems);
  report.num_bad_tags = groups.num_bad_tags;
  report.num_bad_names = groups.num_bad_names;
  return report;
}

double mesh_volume(const TetMesh& mesh) {
  double six = 0.0;
  for (const Tet& t : mesh.tets) {
    if (all_in_range(t, mesh.points.size())) six += six_volume(mesh, t);
  }
  return six / 6.0;
}

void check_indices(const TetMesh& mesh) {
  const size_t num_points = mesh.points.size();
  auto fail = [](const std::string& message) {
    throw Error(ErrorCode::kInternal, "mesh", message);
  };
  for (size_t i = 0; i < mesh.tets.size(); ++i) {
    if (!all_in_range(mesh.tets[i], num_points)) {
      fail("tetrahedron " + std::to_string(i) + " indexes a point outside [0, " +
           std::to_string(num_points) + ")");
    }
  }
  for (size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    if (!all_in_range(mesh.boundary_faces[i], num_points)) {
      fail("boundary face " + std::to_string(i) + " indexes a point outside [0, " +
           std::to_string(num_points) + ")");
    }
  }
  const std::string tags = boundary_tags_problem(mesh.boundary_tags, mesh.boundary_faces.size(),
                                                 mesh.boundary_names.size(), "boundary faces");
  if (!tags.empty()) fail(tags);
}

}  // namespace meshd
