#include "server/job_observer.h"

namespace meshd {

void JobObserver::on_progress(const Progress& p) {
  nodes_ = p.nodes;
  const auto now = Job::Clock::now();
  if (now > job_.deadline()) {
    job_.request_stop(grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                                   "the job's deadline passed while it ran (at iteration " +
                                       std::to_string(p.iteration) + ")"));
  }
  if (now - last_progress_ < kProgressInterval) return;
  last_progress_ = now;
  v1::Progress event;
  event.set_iteration(p.iteration);
  event.set_max_move(p.max_move);
  event.set_retriangulations(p.retriangulations);
  event.set_flips(p.flips);
  event.set_nodes(p.nodes);
  event.set_elapsed_s(p.elapsed_s);
  job_.publish_progress(event);
}

bool JobObserver::wants_snapshot(int iteration) {
  const JobOptions& o = job_.spec().options;
  return o.snapshot_every > 0 && iteration % o.snapshot_every == 0 &&
         nodes_ <= o.snapshot_max_nodes;
}

void JobObserver::on_snapshot(int iteration, const std::vector<Vec2>& points,
                              const std::vector<std::array<int32_t, 3>>* triangles) {
  job_.publish_snapshot(iteration, points, triangles);
}

void JobObserver::on_volume_snapshot(int iteration, const std::vector<Vec3>& points,
                                     const std::vector<std::array<int32_t, 4>>* tetrahedra) {
  job_.publish_snapshot(iteration, points, tetrahedra);
}

}  // namespace meshd
