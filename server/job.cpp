#include "server/job.h"

#include <type_traits>
#include <utility>

namespace meshd {

const char* job_state_name(JobState state) {
  switch (state) {
    case JobState::kQueued:
      return "queued";
    case JobState::kRunning:
      return "running";
    case JobState::kSucceeded:
      return "succeeded";
    case JobState::kFailed:
      return "failed";
    case JobState::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

namespace {

double seconds(Job::Clock::duration d) { return std::chrono::duration<double>(d).count(); }

double unix_now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

bool final_state(JobState s) {
  return s == JobState::kSucceeded || s == JobState::kFailed || s == JobState::kCancelled;
}

v1::JobState to_proto(JobState s) {
  switch (s) {
    case JobState::kQueued:
      return v1::JOB_STATE_QUEUED;
    case JobState::kRunning:
      return v1::JOB_STATE_RUNNING;
    case JobState::kSucceeded:
      return v1::JOB_STATE_SUCCEEDED;
    case JobState::kFailed:
      return v1::JOB_STATE_FAILED;
    case JobState::kCancelled:
      return v1::JOB_STATE_CANCELLED;
  }
  return v1::JOB_STATE_UNSPECIFIED;
}

}  // namespace

Job::Job(std::string id, JobSpec spec, Backend backend, Clock::time_point deadline)
    : id_(std::move(id)),
      spec_(std::move(spec)),
      backend_(backend),
      deadline_(deadline),
      submitted_(Clock::now()),
      submitted_unix_s_(unix_now_s()) {}

void Job::request_stop(const grpc::Status& status) {
  {
    std::lock_guard lock(mutex_);
    if (final_state(state_) || stop_status_) return;
    stop_status_ = status;
  }
  cancel_.store(true, std::memory_order_relaxed);
}

grpc::Status Job::stop_status() const {
  std::lock_guard lock(mutex_);
  return stop_status_.value_or(grpc::Status(grpc::StatusCode::CANCELLED, "job cancelled"));
}

bool Job::set_queue_position(int position, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  if (state_ != JobState::kQueued) return false;
  queue_position_ = position;
  if (queued_seq_ > 0 && (position == told_position_ || now - queued_told_ < kQueuedInterval))
    return false;
  told_position_ = position;
  queued_told_ = now;
  ++queued_seq_;
  return true;
}

bool Job::start(const v1::Started& started) {
  {
    std::lock_guard lock(mutex_);
    if (state_ != JobState::kQueued || stop_status_) return false;
    state_ = JobState::kRunning;
    started_ = started;
    started_at_ = Clock::now();
    started_->set_queue_wait_s(seconds(started_at_ - submitted_));
  }
  wake_subscribers();
  return true;
}

void Job::publish_progress(const v1::Progress& progress) {
  {
    std::lock_guard lock(mutex_);
    if (state_ != JobState::kRunning) return;
    progress_ = progress;
    ++progress_seq_;
  }
  wake_subscribers();
}

namespace {

void append_coordinates(Vec2 p, std::vector<double>& out) {
  out.push_back(p.x);
  out.push_back(p.y);
}
void append_coordinates(Vec3 p, std::vector<double>& out) {
  out.push_back(p.x);
  out.push_back(p.y);
  out.push_back(p.z);
}

}  // namespace

template <typename Point, size_t Corners>
void Job::store_snapshot(int iteration, const std::vector<Point>& points,
                         const std::vector<std::array<int32_t, Corners>>* cells) {
  constexpr int kDimension = std::is_same_v<Point, Vec3> ? 3 : 2;
  {
    std::lock_guard lock(mutex_);
    if (state_ != JobState::kRunning) return;
    snapshot_iteration_ = iteration;
    snapshot_dimension_ = kDimension;
    snapshot_points_.clear();
    snapshot_points_.reserve(kDimension * points.size());
    for (const Point& p : points) append_coordinates(p, snapshot_points_);
    if (cells != nullptr) {
      snapshot_cells_.clear();
      snapshot_cells_.reserve(Corners * cells->size());
      for (const auto& c : *cells)
        snapshot_cells_.insert(snapshot_cells_.end(), c.begin(), c.end());
      ++topology_seq_;
    }
    ++snapshot_seq_;
  }
  wake_subscribers();
}

void Job::publish_snapshot(int iteration, const std::vector<Vec2>& points,
                           const std::vector<std::array<int32_t, 3>>* triangles) {
  store_snapshot(iteration, points, triangles);
}

void Job::publish_snapshot(int iteration, const std::vector<Vec3>& points,
                           const std::vector<std::array<int32_t, 4>>* tetrahedra) {
  store_snapshot(iteration, points, tetrahedra);
}

void Job::drop_problem() {
  spec_.plane = CompiledProblem{};
  if (spec_.volume) *spec_.volume = CompiledProblem3{};
}

void Job::publish_payload(std::shared_ptr<const ResultPayload> payload) {
  {
    std::lock_guard lock(mutex_);
    if (final_state(state_)) return;
    payload_ = std::move(payload);
  }
  wake_subscribers();
}

void Job::succeed(EncodedResult result) {
  {
    std::lock_guard lock(mutex_);
    if (final_state(state_)) return;
    payload_ = std::move(result.payload);
    done_ = std::move(result.done);
    if (started_) {
      done_->mutable_stats()->set_queue_wait_s(started_->queue_wait_s());
      done_->set_backend(started_->backend());
      done_->set_device(started_->device());
    }
    state_ = JobState::kSucceeded;
    finished_at_ = Clock::now();
    // Snapshots are for watching a job settle; nobody needs them once the result is here.
    std::vector<double>().swap(snapshot_points_);
    std::vector<int32_t>().swap(snapshot_cells_);
  }
  wake_subscribers();
}

void Job::finish(const grpc::Status& status) {
  {
    std::lock_guard lock(mutex_);
    if (final_state(state_)) return;
    const auto code = status.error_code();
    state_ = code == grpc::StatusCode::CANCELLED || code == grpc::StatusCode::DEADLINE_EXCEEDED
                 ? JobState::kCancelled
                 : JobState::kFailed;
    final_status_ = status;
    finished_at_ = Clock::now();
    std::vector<double>().swap(snapshot_points_);
    std::vector<int32_t>().swap(snapshot_cells_);
  }
  cancel_.store(true, std::memory_order_relaxed);
  wake_subscribers();
}

JobState Job::state() const {
  std::lock_guard lock(mutex_);
  return state_;
}

bool Job::is_final() const { return final_state(state()); }

Job::Clock::time_point Job::finished_at() const {
  std::lock_guard lock(mutex_);
  return finished_at_;
}

v1::JobInfo Job::info() const {
  v1::JobInfo out;
  out.set_job_id(id_);
  out.set_label(spec_.options.label);
  out.set_priority(spec_.options.priority);
  out.set_submitted_at(submitted_unix_s_);
  std::lock_guard lock(mutex_);
  out.set_state(to_proto(state_));
  if (state_ == JobState::kQueued) out.set_queue_position(queue_position_);
  if (started_) {
    out.set_backend(started_->backend());
    out.set_device(started_->device());
    out.set_queue_wait_s(started_->queue_wait_s());
    const auto end = final_state(state_) ? finished_at_ : Clock::now();
    out.set_run_s(seconds(end - started_at_));
  }
  out.set_iteration(progress_.iteration());
  out.set_nodes(progress_.nodes());
  if (state_ == JobState::kSucceeded) {
    *out.mutable_done() = *done_;
    out.set_nodes(done_->nodes());
    out.set_iteration(done_->stats().iterations());
  }
  if (state_ == JobState::kFailed || state_ == JobState::kCancelled) {
    out.set_error_code(static_cast<int32_t>(final_status_.error_code()));
    out.set_error_message(final_status_.error_message());
  }
  return out;
}

void Job::subscribe(const std::shared_ptr<JobSubscriber>& subscriber) {
  {
    std::lock_guard lock(mutex_);
    std::erase_if(subscribers_, [](const auto& s) { return s.expired(); });
    subscribers_.push_back(subscriber);
  }
  subscriber->wake();
}

void Job::wake_subscribers() {
  std::vector<std::shared_ptr<JobSubscriber>> live;
  {
    std::lock_guard lock(mutex_);
    live.reserve(subscribers_.size());
    for (const auto& s : subscribers_) {
      if (auto p = s.lock()) live.push_back(std::move(p));
    }
  }
  for (const auto& s : live) s->wake();
}

NextEvent Job::next_event(EventCursor& cursor, v1::MeshEvent& event, grpc::Status& status) const {
  event.Clear();
  event.set_job_id(id_);
  std::lock_guard lock(mutex_);
  if (!cursor.started_sent) {
    // Every stream opens with queued, even when a worker took the job at once.
    if (queued_seq_ != cursor.queued_seq &&
        (state_ == JobState::kQueued || cursor.queued_seq == 0)) {
      cursor.queued_seq = queued_seq_;
      event.mutable_queued()->set_position(queue_position_);
      return NextEvent::kEvent;
    }
    if (state_ == JobState::kQueued) return NextEvent::kNone;
    if (started_) {
      cursor.started_sent = true;
      *event.mutable_started() = *started_;
      return NextEvent::kEvent;
    }
  }
  if (state_ == JobState::kRunning) {
    if (progress_seq_ != cursor.progress_seq) {
      cursor.progress_seq = progress_seq_;
      *event.mutable_progress() = progress_;
      return NextEvent::kEvent;
    }
    if (snapshot_seq_ != cursor.snapshot_seq) {
      cursor.snapshot_seq = snapshot_seq_;
      v1::Snapshot& s = *event.mutable_snapshot();
      s.set_iteration(snapshot_iteration_);
      s.mutable_points()->Add(snapshot_points_.begin(), snapshot_points_.end());
      const bool volume = snapshot_dimension_ == 3;
      if (volume) s.set_dimension(3);
      if (cursor.topology_seq != topology_seq_) {
        cursor.topology_seq = topology_seq_;
        if (volume) {
          s.set_has_tetrahedra(true);
          s.mutable_tetrahedra()->Add(snapshot_cells_.begin(), snapshot_cells_.end());
        } else {
          s.set_has_triangles(true);
          s.mutable_triangles()->Add(snapshot_cells_.begin(), snapshot_cells_.end());
        }
      }
      return NextEvent::kEvent;
    }
    if (next_chunk(cursor, event)) return NextEvent::kEvent;
    return NextEvent::kNone;
  }
  if (state_ == JobState::kSucceeded) {
    if (next_chunk(cursor, event)) return NextEvent::kEvent;
    if (!cursor.done_sent) {
      cursor.done_sent = true;
      *event.mutable_done() = *done_;
      return NextEvent::kEvent;
    }
    status = grpc::Status::OK;
    return NextEvent::kFinished;
  }
  status = final_status_;
  return NextEvent::kFinished;
}

bool Job::next_chunk(EventCursor& cursor, v1::MeshEvent& event) const {
  if (!payload_ || cursor.next_chunk >= payload_->chunk_count()) return false;
  const size_t i = cursor.next_chunk++;
  v1::ResultChunk& c = *event.mutable_result_chunk();
  c.set_index(static_cast<uint32_t>(i));
  c.set_count(static_cast<uint32_t>(payload_->chunk_count()));
  c.set_offset(i * payload_->chunk_bytes);
  c.set_total_bytes(payload_->bytes.size());
  const std::string_view data = payload_->chunk(i);
  c.set_data(data.data(), data.size());
  return true;
}

}  // namespace meshd
