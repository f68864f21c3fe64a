// The size field compiled for evaluation on host and device: h(p) = min over terms, each term
//   - a constant h_min (begin == end, grid == kNoGrid),
//   - min(h_max, h_min + slope * |d(p)|) with d the sub-program [begin, end) of `shapes`, or
//   - scale * bilinear(grid) with the grid's header at shapes.params[grid] (regular_grid.h).
// Every term's values lie in [h_min, h_max], so that the bounds of the field need no sampling.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry/program.h"

namespace meshd {

constexpr uint32_t kNoGrid = 0xffffffffu;

struct SizeTermCode {
  double h_min;
  double slope;
  double h_max;
  uint32_t begin;  // instruction range in SizeProgram::shapes; begin == end: no distance
  uint32_t end;
  uint32_t grid = kNoGrid;  // a grid term: its header's offset in SizeProgram::shapes.params
  double scale = 1.0;       // a grid term: the factor on its samples (compile_problem's rescale)
};

struct SizeView {
  ProgramView shapes;
  const SizeTermCode* terms;
  uint32_t count;  // 0: uniform 1
};

struct SizeProgram {
  Program shapes;
  std::vector<SizeTermCode> terms;

  SizeView view() const {
    return {shapes.view(), terms.data(), static_cast<uint32_t>(terms.size())};
  }
  bool uniform() const {
    for (const auto& t : terms)
      if (t.begin != t.end || t.grid != kNoGrid) return false;
    return true;
  }
};

}  // namespace meshd
