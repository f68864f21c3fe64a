// The bounded priority queue of jobs waiting for a worker.
//
// Jobs wait in one line per kind of worker (GPU, CPU), ordered by priority (higher first), then
// by arrival; the capacity bounds both lines together, so that a full queue answers UNAVAILABLE
// at once instead of growing. Every change tells the waiting jobs of that line their position.
// Thread-safe.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "server/job.h"

namespace meshd {

class JobQueue {
 public:
  explicit JobQueue(size_t capacity) : capacity_(capacity) {}

  // Queues `job` in the line of job->worker(). Throws Error(kUnavailable) when the queue is full
  // or closed.
  void push(std::shared_ptr<Job> job);
  // Blocks until a job of kind `worker` waits and returns it, or returns null once the queue is
  // closed.
  std::shared_ptr<Job> pop(Backend worker);
  // Takes `job` out if it still waits; true when it did.
  bool remove(const Job& job);
  // Takes out and returns the jobs whose deadline is before `now`.
  std::vector<std::shared_ptr<Job>> take_expired(Job::Clock::time_point now);
  // Takes out and returns every job of kind `worker` (when the last worker of a kind is gone).
  std::vector<std::shared_ptr<Job>> take_all(Backend worker);
  // Refuses new jobs from now on, wakes every pop (which then returns null) and returns the
  // jobs that were waiting.
  std::vector<std::shared_ptr<Job>> close();

  size_t size() const;
  size_t capacity() const { return capacity_; }

 private:
  struct Entry {
    int priority;
    uint64_t arrival;
    std::shared_ptr<Job> job;
    bool operator<(const Entry& o) const {
      return priority != o.priority ? priority > o.priority : arrival < o.arrival;
    }
  };
  using Line = std::set<Entry>;

  Line& line(Backend worker) { return worker == Backend::kGpu ? gpu_ : cpu_; }
  void renumber(const Line& line);

  const size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  Line gpu_, cpu_;
  uint64_t arrivals_ = 0;
  bool closed_ = false;
};

}  // namespace meshd
