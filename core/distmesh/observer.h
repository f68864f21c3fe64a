// How a running DistMesh job reports to whoever started it (the service, the benchmark).
// Every method is called on the job's thread between iterations; keep them cheap.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/common/vec3.h"

namespace meshd {

struct Progress {
  int iteration = 0;
  double max_move = 0.0;  // largest interior move of the last step, relative to h0
  int retriangulations = 0;
  int64_t flips = 0;  // edge flips of topology repairs so far
  int64_t nodes = 0;
  double elapsed_s = 0.0;
};

class Observer {
 public:
  virtual ~Observer() = default;
  virtual void on_progress(const Progress&) {}
  // Asked once for each iteration, in order, at most a batch of steps ahead (engine.h); true
  // means on_snapshot follows right after that iteration.
  virtual bool wants_snapshot(int /*iteration*/) { return false; }
  // points: #N by 2. triangles: #M by 3, or null when the topology did not change since the
  // last snapshot.
  virtual void on_snapshot(int /*iteration*/, const std::vector<Vec2>& /*points*/,
                           const std::vector<std::array<int32_t, 3>>* /*triangles*/) {}
  // The same for a volume (the 3D loop calls it in on_snapshot's place): points #N by 3;
  // tetrahedra #M by 4, or null when unchanged.
  virtual void on_volume_snapshot(int /*iteration*/, const std::vector<Vec3>& /*points*/,
                                  const std::vector<std::array<int32_t, 4>>* /*tetrahedra*/) {}
};

}  // namespace meshd
