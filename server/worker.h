// A worker: one thread that takes the jobs of its kind (GPU or CPU) from the queue and runs each
// on its own engine, so that a GPU worker owns its device, stream and arena between jobs.
//
// A job that fails fails alone: the worker finishes it with its status and takes the next one.
// When an engine throws anything but a request error (a CUDA fault, say), the worker rebuilds
// it before the next job; when it cannot, the worker retires and says so through its hooks.
#pragma once

#include <atomic>
#include <functional>
#include <future>
#include <latch>
#include <memory>
#include <string>
#include <thread>

#include "core/distmesh/observer.h"
#include "server/job_queue.h"
#include "server/metrics.h"
#include "server/result_encoding.h"
#include "server/worker_engine.h"

namespace meshd {

class Worker {
 public:
  struct Hooks {
    std::function<void(Job&)> finished;    // after the job reached its final state
    std::function<void(Worker&)> retired;  // the worker stopped for good (its engine is gone)
  };

  Worker(std::string name, Backend kind, WorkerEngineFactory factory, JobQueue& queue,
         Metrics& metrics, Hooks hooks);
  ~Worker();
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Starts the worker's thread: it builds the engine and meshes small disks on it (worker.cpp
  // says which), then waits for take_jobs(). The warm-up runs on the thread that runs the jobs,
  // so that the thread's own heap and state are warm for the first one. The future holds the
  // warm-up's outcome: the exception when the engine cannot be built or a mesh fails (the
  // thread has ended then).
  std::future<void> start();
  // Lets the warm worker take jobs. The thread ends when the queue closes.
  void take_jobs();
  // Lets a worker still waiting go on (the queue, closed, ends it) and waits for its thread.
  void join();

  const std::string& name() const { return name_; }
  Backend kind() const { return kind_; }
  // Where its jobs run ("cpu (2 threads)"); empty before the warm-up.
  const std::string& device() const { return device_; }
  bool retired() const { return retired_.load(); }

 private:
  void warm_up();
  void loop();
  void run(Job& job);
  // The job's mesh on this worker's engine, encoded; `t` is when it started.
  EncodedResult run_plane(Job& job, Observer& observer, Job::Clock::time_point t);
  // The result's payload, published to the job's streams, and then its done event.
  template <typename Result>
  EncodedResult encode_and_publish(Job& job, const Result& result);
  EncodedResult run_volume(Job& job, Observer& observer, Job::Clock::time_point t);
  bool rebuild_engine();

  const std::string name_;
  const Backend kind_;
  const WorkerEngineFactory factory_;
  JobQueue& queue_;
  Metrics& metrics_;
  const Hooks hooks_;
  std::unique_ptr<WorkerEngine> engine_;
  std::string device_;
  std::atomic<bool> retired_{false};
  std::latch may_take_jobs_{1};
  std::atomic<bool> took_jobs_{false};
  std::thread thread_;
};

}  // namespace meshd
