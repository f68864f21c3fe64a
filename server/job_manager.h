// The jobs the service holds. It validates and queues new jobs, finds them by id, cancels them,
// expires queued jobs at their deadline and forgets finished ones after the retention time. It
// owns the queue and the workers; the gRPC handlers only call it.
//
// Routing: a job asking for the GPU goes to the GPU line (FAILED_PRECONDITION when the server
// has no GPU worker), one asking for the CPU to the CPU line, and BACKEND_AUTO to the shared
// line when the server has workers of both kinds (the queue then sends it where it will finish
// first), else to the line of the kind it has.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/common/thread_pool.h"
#include "meshd/v1/service.pb.h"
#include "server/job_queue.h"
#include "server/metrics.h"
#include "server/request_conversion.h"
#include "server/worker.h"

namespace meshd {

struct WorkerSpec {
  std::string name;  // "gpu0", "cpu1"
  Backend kind;      // kGpu or kCpu
  WorkerEngineFactory factory;
  unsigned threads = 1;  // the host's threads that a CPU worker's jobs keep busy
};

struct JobManagerOptions {
  ConversionLimits limits;
  size_t queue_capacity = 64;
  std::chrono::milliseconds retention{std::chrono::minutes(10)};  // finished jobs kept this long
  size_t max_retained = 1000;  // and at most this many (the oldest go first)
};

class JobManager {
 public:
  JobManager(JobManagerOptions options, std::vector<WorkerSpec> workers, Metrics& metrics);
  ~JobManager();
  JobManager(const JobManager&) = delete;
  JobManager& operator=(const JobManager&) = delete;

  // Warms every worker at once (each builds its engine and meshes small disks on its own
  // thread), then lets them take jobs. Throws when a worker cannot warm up.
  void start();

  // Validates `request` and queues it with `deadline` (Clock::time_point::max() for none).
  // Throws Error: kInvalidArgument / kResourceExhausted (the request), kFailedPrecondition (a
  // GPU asked of a server without one), kUnavailable (queue full, shutting down).
  std::shared_ptr<Job> submit(const v1::MeshRequest& request, Job::Clock::time_point deadline);
  // Throws Error(kNotFound) naming "job_id".
  std::shared_ptr<Job> find(const std::string& id) const;
  // Stops a queued or running job with `status`; a final job is left alone. Returns its info.
  v1::JobInfo cancel(const std::string& id, const grpc::Status& status);
  std::vector<v1::JobInfo> list(v1::JobState filter) const;

  // Refuses new jobs from now on (kUnavailable), the first step of a shutdown.
  void stop_accepting() { accepting_.store(false); }
  // Shutdown: refuses new jobs, lets queued and running ones finish for up to `grace`, then
  // cancels the rest (UNAVAILABLE for queued, CANCELLED for running ones) and joins the workers.
  void drain(std::chrono::milliseconds grace);

  int64_t live_jobs() const { return live_.load(); }
  bool has_gpu() const;
  // "gpu0: NVIDIA H100 ... (device 0)" for each worker.
  std::vector<std::string> describe_workers() const;

 private:
  void on_finished(Job& job);
  void on_retired(Worker& worker);
  void housekeeping();
  void finish_queued(const std::shared_ptr<Job>& job, const grpc::Status& status);
  std::string new_id();

  const JobManagerOptions options_;
  // One thread per hardware thread for the node estimates of new requests (a long polygon's
  // takes milliseconds); admissions that find it busy survey on their own threads.
  ThreadPool admission_pool_;
  Metrics& metrics_;
  JobQueue queue_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::atomic<int> live_gpu_workers_{0};
  int cpu_workers_ = 0;
  unsigned cpu_threads_ = 1;  // the most threads of one CPU worker
  std::atomic<int64_t> live_{0};
  std::atomic<bool> accepting_{true};

  mutable std::mutex mutex_;  // jobs_, finished_order_, stop_
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::deque<std::string> finished_order_;
  uint64_t next_id_ = 0;
  uint64_t id_salt_ = 0;
  bool stop_ = false;
  std::condition_variable wake_housekeeping_;
  std::thread housekeeping_;
};

}  // namespace meshd
