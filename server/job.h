// One mesh job as the service holds it, and what its event streams read.
//
// A job moves queued → running → succeeded | failed | cancelled, or from queued straight to
// failed or cancelled, and never leaves a final state. Its events are kept here and only here:
// the latest queue position, the start, the latest progress and the latest snapshot (a slow
// reader gets the newest, never a backlog: memory per job is bounded by one snapshot), and the
// whole encoded result (chunks are never dropped; the result is kept for retention anyway),
// whose chunks go out from when the worker publishes the payload, before its checksum.
// Each change bumps a sequence number and wakes the subscribers (a queue position at most every
// kQueuedInterval), which pull with next_event at their own pace through an EventCursor of their
// own. Thread-safe: one mutex guards the state, and subscribers are woken with it released.
#pragma once

#include <grpcpp/support/status.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/common/vec2.h"
#include "core/common/vec3.h"
#include "meshd/v1/service.pb.h"
#include "server/job_spec.h"
#include "server/result_encoding.h"

namespace meshd {

enum class JobState { kQueued, kRunning, kSucceeded, kFailed, kCancelled };

const char* job_state_name(JobState state);

// A stream that reads a job's events. wake() is called whenever something new may be there,
// from any thread, never with the job's mutex held.
class JobSubscriber {
 public:
  virtual ~JobSubscriber() = default;
  virtual void wake() = 0;
};

// What one reader has already received.
struct EventCursor {
  uint64_t queued_seq = 0;
  bool started_sent = false;
  uint64_t progress_seq = 0;
  uint64_t snapshot_seq = 0;
  uint64_t topology_seq = 0;  // of the triangles this reader holds
  size_t next_chunk = 0;
  bool done_sent = false;
};

enum class NextEvent { kNone, kEvent, kFinished };

class Job {
 public:
  using Clock = std::chrono::steady_clock;

  // `backend` is the kind of worker that may run it: kGpu, kCpu, or kAuto for either (the queue
  // decides which); `deadline` is Clock::time_point::max() when none.
  Job(std::string id, JobSpec spec, Backend backend, Clock::time_point deadline);

  const std::string& id() const { return id_; }
  const JobSpec& spec() const { return spec_; }
  // Frees the compiled problem once no worker will mesh it (the job finished, ran or not): a
  // retained job keeps what GetJob and its result need, not its geometry.
  void drop_problem();
  Backend backend() const { return backend_; }
  Clock::time_point deadline() const { return deadline_; }
  Clock::time_point submitted() const { return submitted_; }

  // ---- Control -------------------------------------------------------------------------------
  // The flag the DistMesh loop polls between iterations.
  const std::atomic<bool>* cancel_flag() const { return &cancel_; }
  // Asks the job to stop with `status` (CANCELLED or DEADLINE_EXCEEDED). A running job stops
  // within one iteration and its worker finishes it with this status; a queued job is finished
  // by whoever takes it out of the queue. The first reason wins.
  void request_stop(const grpc::Status& status);
  grpc::Status stop_status() const;

  // ---- Written by the queue and the worker -----------------------------------------------------
  // How often at most a queued job's streams are told that its position changed. Each pop moves
  // every job behind it, so telling each change costs a write per waiting job per pop; with a
  // hundred jobs waiting that bounded the whole server near 500 jobs/s (issue 15).
  static constexpr std::chrono::milliseconds kQueuedInterval{100};

  // Records the job's place in its line (info() has it at once) at `now`. Its streams are told
  // (a queued event with the latest position) the first time and then on a change at least
  // kQueuedInterval after they were last told; a change within it is told by the next call
  // after the interval (the queue repeats the positions periodically for that: retell). True
  // when they should be told: the caller then calls wake_subscribers, with no lock of its own
  // held.
  bool set_queue_position(int position, Clock::time_point now);
  // Marks the job running; false when it was stopped while queued (then it must not run).
  bool start(const v1::Started& started);
  void publish_progress(const v1::Progress& progress);
  // points: #N by 2; triangles: #M by 3, or null when unchanged since the last snapshot.
  void publish_snapshot(int iteration, const std::vector<Vec2>& points,
                        const std::vector<std::array<int32_t, 3>>* triangles);
  // A volume's: points #N by 3; tetrahedra #M by 4, or null when unchanged.
  void publish_snapshot(int iteration, const std::vector<Vec3>& points,
                        const std::vector<std::array<int32_t, 4>>* tetrahedra);
  // The result's payload ahead of succeed(): the streams send its chunks while the worker takes
  // its checksum. succeed() then carries the same payload.
  void publish_payload(std::shared_ptr<const ResultPayload> payload);
  void succeed(EncodedResult result);
  // Finishes with a non-OK status: CANCELLED and DEADLINE_EXCEEDED count as cancelled, any
  // other code as failed. No effect on a job already final.
  void finish(const grpc::Status& status);

  // ---- Read by the service -------------------------------------------------------------------
  JobState state() const;
  bool is_final() const;
  Clock::time_point finished_at() const;
  v1::JobInfo info() const;

  void subscribe(const std::shared_ptr<JobSubscriber>& subscriber);
  // The next event for a reader at `cursor`, which it advances. kFinished sets `status`: the
  // stream ends there (OK after done).
  NextEvent next_event(EventCursor& cursor, v1::MeshEvent& event, grpc::Status& status) const;
  // Tells the subscribers that something may be new; call it with no lock held.
  void wake_subscribers();

 private:
  // The cursor's next chunk of the payload into `event`; false when all were sent. mutex_ held.
  bool next_chunk(EventCursor& cursor, v1::MeshEvent& event) const;
  // publish_snapshot's body, for either dimension.
  template <typename Point, size_t Corners>
  void store_snapshot(int iteration, const std::vector<Point>& points,
                      const std::vector<std::array<int32_t, Corners>>* cells);

  const std::string id_;
  JobSpec spec_;  // const but for drop_problem
  const Backend backend_;
  const Clock::time_point deadline_;
  const Clock::time_point submitted_;
  const double submitted_unix_s_;
  std::atomic<bool> cancel_{false};

  mutable std::mutex mutex_;
  JobState state_ = JobState::kQueued;
  std::optional<grpc::Status> stop_status_;
  grpc::Status final_status_;
  Clock::time_point started_at_{}, finished_at_{};

  int queue_position_ = 0;
  uint64_t queued_seq_ = 0;          // bumped each time the streams are told the position
  int told_position_ = 0;            // the position they were last told
  Clock::time_point queued_told_{};  // when they were last told
  std::optional<v1::Started> started_;
  v1::Progress progress_;
  uint64_t progress_seq_ = 0;
  int snapshot_iteration_ = 0;
  int snapshot_dimension_ = 2;
  std::vector<double> snapshot_points_;  // x0, y0, x1, ... (x0, y0, z0, ... in 3D)
  std::vector<int32_t> snapshot_cells_;  // triangles, or tetrahedra in 3D
  uint64_t snapshot_seq_ = 0;
  uint64_t topology_seq_ = 0;
  std::shared_ptr<const ResultPayload> payload_;  // published ahead, or with the result
  std::optional<v1::Done> done_;                  // once succeeded

  std::vector<std::weak_ptr<JobSubscriber>> subscribers_;
};

}  // namespace meshd
