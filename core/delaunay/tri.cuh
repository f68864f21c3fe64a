// A triangle's three corners, or its three neighbours, as the device's triangulations keep them
// (on the host and the device): slot k across the edge opposite corner k, -1 on the hull.
#pragma once

#include <cstdint>

#include "core/common/hd.h"

namespace meshd {

struct Tri {
  int32_t v[3];
};

// The slot of `nbr` (a triangle's neighbours) that holds triangle `value`.
MESHD_HD inline int slot_of(const Tri& nbr, int32_t value) {
  return nbr.v[0] == value ? 0 : (nbr.v[1] == value ? 1 : 2);
}

}  // namespace meshd
