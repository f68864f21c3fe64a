// The boundary of a tetrahedral mesh: the faces that only one tetrahedron has.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace meshd {

// The faces of `tets` (#M by 4, positively oriented) that no other tetrahedron shares, #F by 3,
// each turning counter-clockwise seen from outside, in the order of their tetrahedra (and of
// the opposite vertex within one).
std::vector<std::array<int32_t, 3>> tet_boundary_faces(
    const std::vector<std::array<int32_t, 4>>& tets);

// Face k of a positively oriented tetrahedron t, opposite t[k], turning counter-clockwise seen
// from outside.
inline std::array<int32_t, 3> tet_face(const std::array<int32_t, 4>& t, int k) {
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  return {t[kFace[k][0]], t[kFace[k][1]], t[kFace[k][2]]};
}

}  // namespace meshd
