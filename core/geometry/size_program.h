// The size field compiled for evaluation on host and device: h(p) = min over terms, each term
// either a constant or min(h_max, h_min + slope * |d(p)|) with d a sub-program of `shapes`.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry/program.h"

namespace meshd {

struct SizeTermCode {
  double h_min;
  double slope;
  double h_max;
  uint32_t begin;  // instruction range in SizeProgram::shapes; begin == end: constant h_min
  uint32_t end;
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
      if (t.begin != t.end) return false;
    return true;
  }
};

}  // namespace meshd
