// The DistMesh loop's observer for a service job: forwards progress (at most one event per
// kProgressInterval, so that the streams cost nothing measurable on fast GPU iterations) and
// the snapshots the request asked for to the Job, and stops the job at its deadline.
#pragma once

#include <chrono>

#include "core/distmesh/observer.h"
#include "server/job.h"

namespace meshd {

class JobObserver final : public Observer {
 public:
  static constexpr std::chrono::milliseconds kProgressInterval{10};

  explicit JobObserver(Job& job) : job_(job) {}

  void on_progress(const Progress& progress) override;
  bool wants_snapshot(int iteration) override;
  void on_snapshot(int iteration, const std::vector<Vec2>& points,
                   const std::vector<std::array<int32_t, 3>>* triangles) override;
  void on_volume_snapshot(int iteration, const std::vector<Vec3>& points,
                          const std::vector<std::array<int32_t, 4>>* tetrahedra) override;

 private:
  Job& job_;
  Job::Clock::time_point last_progress_{};
  int64_t nodes_ = 0;
};

}  // namespace meshd
