#include "core/geometry/regular_grid.h"

#include "core/geometry/program.h"

namespace meshd {

uint32_t append_grid(Program& program, Vec2 origin, Vec2 spacing, uint32_t nx, uint32_t ny,
                     const float* values) {
  const auto offset = static_cast<uint32_t>(program.params.size());
  const auto first = program.samples.size();
  program.params.insert(program.params.end(),
                        {origin.x, origin.y, spacing.x, spacing.y, double(nx), double(ny),
                         double(first)});
  program.samples.insert(program.samples.end(), values, values + size_t(nx) * ny);
  return offset;
}

}  // namespace meshd
