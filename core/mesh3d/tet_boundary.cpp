#include "core/mesh3d/tet_boundary.h"

#include <algorithm>

namespace meshd {

std::vector<std::array<int32_t, 3>> tet_boundary_faces(
    const std::vector<std::array<int32_t, 4>>& tets) {
  // Every face as (sorted corners, tetrahedron * 4 + k), sorted: a face two tetrahedra share
  // appears twice in a row.
  struct Entry {
    std::array<int32_t, 3> key;
    int64_t slot;
  };
  std::vector<Entry> faces;
  faces.reserve(4 * tets.size());
  for (size_t t = 0; t < tets.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<int32_t, 3> key = tet_face(tets[t], k);
      std::sort(key.begin(), key.end());
      faces.push_back({key, static_cast<int64_t>(4 * t + k)});
    }
  std::sort(faces.begin(), faces.end(),
            [](const Entry& a, const Entry& b) { return a.key < b.key; });
  std::vector<int64_t> once;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) once.push_back(faces[i].slot);
    i = j;
  }
  std::sort(once.begin(), once.end());
  std::vector<std::array<int32_t, 3>> out;
  out.reserve(once.size());
  for (int64_t slot : once) out.push_back(tet_face(tets[slot / 4], static_cast<int>(slot % 4)));
  return out;
}

}  // namespace meshd
