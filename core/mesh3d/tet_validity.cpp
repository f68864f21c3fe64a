#include "core/mesh3d/tet_validity.h"

#include <algorithm>
#include <map>

#include "core/common/error.h"
#include "core/mesh3d/tet_boundary.h"

namespace meshd {
namespace {

constexpr int kProblemsPerKind = 3;

class Problems {
 public:
  explicit Problems(TetValidityReport& report) : report_(report) {}
  // Records `what` unless kProblemsPerKind of this kind were recorded already; counts it anyway.
  void add(const std::string& kind, const std::string& what) {
    if (++count_[kind] <= kProblemsPerKind) report_.problems.push_back(what);
  }
  ~Problems() {
    for (const auto& [kind, n] : count_)
      if (n > kProblemsPerKind)
        report_.problems.push_back(std::to_string(n) + " " + kind + " in all");
  }

 private:
  TetValidityReport& report_;
  std::map<std::string, int> count_;
};

std::string index_problem(const TetMesh& mesh) {
  const auto n = static_cast<int64_t>(mesh.points.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    for (int32_t v : mesh.tets[t])
      if (v < 0 || v >= n) return "tets[" + std::to_string(t) + "] has index " + std::to_string(v);
  for (size_t f = 0; f < mesh.boundary_faces.size(); ++f)
    for (int32_t v : mesh.boundary_faces[f])
      if (v < 0 || v >= n)
        return "boundary_faces[" + std::to_string(f) + "] has index " + std::to_string(v);
  if (mesh.boundary_tags.size() != mesh.boundary_faces.size())
    return "boundary_tags has " + std::to_string(mesh.boundary_tags.size()) + " entries for " +
           std::to_string(mesh.boundary_faces.size()) + " boundary faces";
  const auto groups = static_cast<int32_t>(mesh.boundary_names.size());
  for (size_t f = 0; f < mesh.boundary_tags.size(); ++f)
    if (mesh.boundary_tags[f] < 0 || mesh.boundary_tags[f] >= groups)
      return "boundary_tags[" + std::to_string(f) + "] = " + std::to_string(mesh.boundary_tags[f]) +
             " is not a group";
  return "";
}

}  // namespace

void check_indices(const TetMesh& mesh) {
  const std::string problem = index_problem(mesh);
  if (!problem.empty()) throw Error(ErrorCode::kInternal, "mesh", problem);
}

TetValidityReport check_tet_validity(const TetMesh& mesh) {
  TetValidityReport report;
  const std::string index = index_problem(mesh);
  if (!index.empty()) {
    report.problems.push_back(index);
    return report;
  }
  {
    Problems problems(report);
    std::vector<char> used(mesh.points.size(), 0);
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
      const auto& v = mesh.tets[t];
      for (int32_t i : v) used[i] = 1;
      const Vec3 a = mesh.points[v[0]];
      const double six_volume =
          dot(mesh.points[v[1]] - a, cross(mesh.points[v[2]] - a, mesh.points[v[3]] - a));
      if (!(six_volume > 0.0))
        problems.add("non-positive volumes", "tets[" + std::to_string(t) + "] has volume " +
                                                 std::to_string(six_volume / 6));
    }
    for (size_t i = 0; i < used.size(); ++i)
      if (!used[i]) problems.add("unused points", "points[" + std::to_string(i) + "] is unused");

    // Each face: how many tetrahedra have it, and with which turn.
    std::map<std::array<int32_t, 3>, std::pair<int, std::array<int32_t, 3>>> faces;
    for (const auto& t : mesh.tets)
      for (int k = 0; k < 4; ++k) {
        const auto f = tet_face(t, k);
        auto key = f;
        std::sort(key.begin(), key.end());
        auto& entry = faces[key];
        ++entry.first;
        entry.second = f;
      }
    for (const auto& [key, entry] : faces)
      if (entry.first > 2)
        problems.add("faces shared by more than two tetrahedra",
                     "a face is shared by " + std::to_string(entry.first) + " tetrahedra");
    // Two tetrahedra on the same side of a face have it with the same turn: found above as one
    // face, yet their volumes overlap; the boundary check below cannot see it, the turn can.
    std::map<std::array<int32_t, 3>, int> turns;
    for (const auto& t : mesh.tets)
      for (int k = 0; k < 4; ++k)
        if (++turns[tet_face(t, k)] > 1)
          problems.add("faces turned the same way twice", "two tetrahedra overlap at a face");

    const auto expected = tet_boundary_faces(mesh.tets);
    std::map<std::array<int32_t, 3>, int> listed;
    for (const auto& f : mesh.boundary_faces) ++listed[f];
    for (const auto& f : expected) {
      const auto it = listed.find(f);
      if (it == listed.end() || it->second == 0) {
        problems.add("missing boundary faces", "a boundary face is not listed (or turned in)");
        continue;
      }
      --it->second;
    }
    for (const auto& [f, n] : listed)
      if (n > 0) problems.add("extra boundary faces", "a listed boundary face is not one");
  }
  return report;
}

}  // namespace meshd
