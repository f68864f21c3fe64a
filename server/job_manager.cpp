#include "server/job_manager.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <future>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "server/status_mapping.h"

namespace meshd {

namespace {

const char* outcome(JobState state) {
  switch (state) {
    case JobState::kSucceeded:
      return "succeeded";
    case JobState::kCancelled:
      return "cancelled";
    default:
      return "failed";
  }
}

// How often housekeeping looks for expired queued jobs and for results past retention.
constexpr std::chrono::milliseconds kHousekeepingInterval{20};

}  // namespace

JobManager::JobManager(JobManagerOptions options, std::vector<WorkerSpec> workers, Metrics& metrics)
    : options_(std::move(options)), metrics_(metrics), queue_(options_.queue_capacity) {
  id_salt_ = std::random_device{}() & 0xffffffu;
  for (WorkerSpec& w : workers) {
    if (w.kind == Backend::kCpu) {
      ++cpu_workers_;
      cpu_threads_ = std::max(cpu_threads_, w.threads);
    }
    Worker::Hooks hooks{[this](Job& job) { on_finished(job); },
                        [this](Worker& worker) { on_retired(worker); }};
    workers_.push_back(std::make_unique<Worker>(std::move(w.name), w.kind, std::move(w.factory),
                                                queue_, metrics_, std::move(hooks)));
  }
}

JobManager::~JobManager() { drain(std::chrono::milliseconds(0)); }

void JobManager::start() {
  // The workers warm up at once, each on its own thread; a failed warm-up fails the start. The
  // log's registry is built on first use: here, before their threads, so that they only read it
  // (its guard is in a library that ThreadSanitizer does not see, which would report a race).
  spdlog::info("warming up {} workers", workers_.size());
  std::vector<std::future<void>> warm;
  for (auto& w : workers_) warm.push_back(w->start());
  for (size_t i = 0; i < workers_.size(); ++i) {
    warm[i].get();
    if (workers_[i]->kind() == Backend::kGpu) ++live_gpu_workers_;
  }
  queue_.set_gpu_workers(live_gpu_workers_.load());
  // A GPU worker's host thread launches and waits on latency-bound work, and CPU work on every
  // core slows it: on 16 cores, 8 GPU workers beside 16 single-thread CPU workers served 515
  // jobs/s of ~2k nodes, beside 8 of them 663 (bench/RESULTS.md). While GPU workers take jobs,
  // the CPU workers run at most as many shared jobs as the cores left after one per GPU worker
  // hold.
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int spare = std::max(1, cores - live_gpu_workers_.load());
  queue_.set_shared_cpu_limit(std::max(1, spare / static_cast<int>(std::max(1u, cpu_threads_))));
  for (auto& w : workers_) w->take_jobs();
  housekeeping_ = std::thread([this] { housekeeping(); });
}

bool JobManager::has_gpu() const { return live_gpu_workers_.load() > 0; }

std::vector<std::string> JobManager::describe_workers() const {
  std::vector<std::string> out;
  for (const auto& w : workers_) out.push_back(w->name() + ": " + w->device());
  return out;
}

std::string JobManager::new_id() {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "j%010llu-%06llx",
                static_cast<unsigned long long>(++next_id_),
                static_cast<unsigned long long>(id_salt_));
  return buffer;
}

std::shared_ptr<Job> JobManager::submit(const v1::MeshRequest& request,
                                        Job::Clock::time_point deadline) {
  if (!accepting_.load()) throw Error(ErrorCode::kUnavailable, "", "the server is shutting down");
  JobSpec spec = to_job_spec(request, options_.limits, &admission_pool_);
  if (spec.options.timeout_s > 0) {
    const auto timeout = std::chrono::duration_cast<Job::Clock::duration>(
        std::chrono::duration<double>(spec.options.timeout_s));
    deadline = std::min(deadline, Job::Clock::now() + timeout);
  }
  Backend worker = spec.options.backend;
  if (worker == Backend::kGpu && !has_gpu()) {
    throw Error(ErrorCode::kFailedPrecondition, "options.backend",
                "BACKEND_GPU asked, but this server has no working GPU: use BACKEND_AUTO or "
                "BACKEND_CPU");
  }
  if (spec.volume && worker == Backend::kAuto) {
    // A 3D job's time is mostly its host parts (the triangulations, the finish), on a GPU worker
    // too: BACKEND_AUTO leaves the GPU workers to plane jobs where CPU workers exist.
    worker = cpu_workers_ > 0 ? Backend::kCpu : Backend::kGpu;
  }
  if (worker == Backend::kAuto && (!has_gpu() || cpu_workers_ == 0))
    worker = has_gpu() ? Backend::kGpu : Backend::kCpu;

  std::shared_ptr<Job> job;
  {
    std::lock_guard lock(mutex_);
    job = std::make_shared<Job>(new_id(), std::move(spec), worker, deadline);
    jobs_.emplace(job->id(), job);
  }
  ++live_;
  metrics_.add_live_jobs(1);
  spdlog::info("job {} queued for {}: about {:.0f} nodes, priority {}{}", job->id(),
               backend_name(worker), job->spec().estimated_nodes, job->spec().options.priority,
               job->spec().options.label.empty() ? "" : ", label " + job->spec().options.label);
  try {
    queue_.push(job);
  } catch (const Error& e) {
    spdlog::info("job {} refused: {}", job->id(), e.what());
    --live_;
    metrics_.add_live_jobs(-1);
    std::lock_guard lock(mutex_);
    jobs_.erase(job->id());
    throw;
  }
  metrics_.set_queue_depth(static_cast<int64_t>(queue_.size()));
  return job;
}

std::shared_ptr<Job> JobManager::find(const std::string& id) const {
  std::lock_guard lock(mutex_);
  const auto it = jobs_.find(id);
  if (it == jobs_.end()) {
    throw Error(ErrorCode::kNotFound, "job_id",
                "no job " + quote_input(id) + " on this server (finished jobs are kept for " +
                    std::to_string(options_.retention.count() / 1000) + " s)");
  }
  return it->second;
}

void JobManager::finish_queued(const std::shared_ptr<Job>& job, const grpc::Status& status) {
  job->finish(status);
  on_finished(*job);
}

v1::JobInfo JobManager::cancel(const std::string& id, const grpc::Status& status) {
  std::shared_ptr<Job> job = find(id);
  job->request_stop(status);
  // A queued job never reaches a worker: finish it here. A running one stops within an
  // iteration and its worker finishes it.
  if (queue_.remove(*job)) {
    metrics_.set_queue_depth(static_cast<int64_t>(queue_.size()));
    finish_queued(job, job->stop_status());
  }
  return job->info();
}

std::vector<v1::JobInfo> JobManager::list(v1::JobState filter) const {
  std::vector<std::shared_ptr<Job>> jobs;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, job] : jobs_) jobs.push_back(job);
  }
  std::vector<v1::JobInfo> out;
  for (const auto& job : jobs) {
    v1::JobInfo info = job->info();
    if (filter == v1::JOB_STATE_UNSPECIFIED || info.state() == filter)
      out.push_back(std::move(info));
  }
  return out;
}

void JobManager::on_finished(Job& job) {
  job.drop_problem();
  metrics_.count_job(outcome(job.state()));
  --live_;
  metrics_.add_live_jobs(-1);
  std::lock_guard lock(mutex_);
  finished_order_.push_back(job.id());
  while (finished_order_.size() > options_.max_retained) {
    jobs_.erase(finished_order_.front());
    finished_order_.pop_front();
  }
}

void JobManager::on_retired(Worker& worker) {
  if (worker.kind() != Backend::kGpu) return;
  const int left = --live_gpu_workers_;
  queue_.set_gpu_workers(left);
  if (left > 0) return;
  spdlog::error("no GPU worker left: new and shared jobs run on the CPU, queued GPU jobs fail");
  for (const auto& job : queue_.take_all(Backend::kGpu)) {
    finish_queued(job, grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                    "the server's last GPU failed before this job started"));
  }
}

void JobManager::housekeeping() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    wake_housekeeping_.wait_for(lock, kHousekeepingInterval);
    const auto now = Job::Clock::now();
    lock.unlock();
    for (const auto& job : queue_.take_expired(now)) {
      finish_queued(job, grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                                      "the job's deadline passed while it was queued"));
    }
    queue_.retell_positions();
    lock.lock();
    while (!finished_order_.empty()) {
      const auto it = jobs_.find(finished_order_.front());
      if (it != jobs_.end() && now - it->second->finished_at() < options_.retention) break;
      if (it != jobs_.end()) jobs_.erase(it);
      finished_order_.pop_front();
    }
  }
}

void JobManager::drain(std::chrono::milliseconds grace) {
  if (!accepting_.exchange(false) && workers_.empty()) return;
  const auto until = Job::Clock::now() + grace;
  while (live_.load() > 0 && Job::Clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  for (const auto& job : queue_.close()) {
    finish_queued(job, grpc::Status(grpc::StatusCode::UNAVAILABLE,
                                    "the server shut down before this job started"));
  }
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, job] : jobs_) {
      job->request_stop(
          grpc::Status(grpc::StatusCode::CANCELLED, "the server shut down while this job ran"));
    }
    stop_ = true;
  }
  wake_housekeeping_.notify_all();
  for (auto& w : workers_) w->join();
  if (housekeeping_.joinable()) housekeeping_.join();
  workers_.clear();
}

}  // namespace meshd
