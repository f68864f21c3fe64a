// The bounded priority queue of jobs waiting for a worker, and where each job goes.
//
// Jobs wait in three lines: one for jobs that asked for the GPU, one for the CPU, and one for
// jobs any worker may run (BACKEND_AUTO on a server with both kinds). Each line is ordered by
// priority (higher first), then by arrival; the capacity bounds all lines together, so that a
// full queue answers UNAVAILABLE at once instead of growing. Every change gives the waiting
// jobs of that line their position (Job::set_queue_position says when their streams hear of it);
// their streams are woken after the queue's mutex is released, so that no worker waits for
// another job's event to be written.
//
// The queue is work-conserving: a free worker takes the first job of its own line or of the
// shared line, whichever comes first. A GPU worker takes any shared job; a CPU worker takes the
// first shared job that it would finish before the GPU workers would, counting the work they
// have queued and running ahead of it (a RunTimeModel, trained on the workers' measured runs,
// says how long each job takes where). So small jobs spill onto idle CPU workers when the GPUs
// are busy, and large ones wait for a GPU; and no more of them at once than the limit that keeps
// some cores for the GPU workers' own threads (set_shared_cpu_limit). Thread-safe.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "server/job.h"
#include "server/run_time_model.h"

namespace meshd {

class JobQueue {
 public:
  explicit JobQueue(size_t capacity) : capacity_(capacity) {}

  // How many GPU workers take jobs now (the shared line's jobs go to the CPU workers alone when
  // none is left).
  void set_gpu_workers(int count);
  // While GPU workers take jobs, the CPU workers run at most `jobs` shared jobs at once (0: no
  // limit; jobs of the CPU's own line are not counted or held back).
  void set_shared_cpu_limit(int jobs);

  // Queues `job` in the line of job->backend(). Throws Error(kUnavailable) when the queue is
  // full or closed.
  void push(std::shared_ptr<Job> job);
  // Blocks until a job that a worker of kind `worker` should run waits and returns it, or
  // returns null once the queue is closed. The job counts as running on `worker` until done().
  std::shared_ptr<Job> pop(Backend worker);
  // The job popped by a worker of `kind` has ended after `seconds`; `succeeded` says whether
  // that time teaches how long such jobs take.
  void done(const Job& job, Backend kind, double seconds, bool succeeded);
  // A run outside the queue (a worker's warm-up) that teaches how long jobs take.
  void observe_run(Backend kind, double nodes, double seconds);
  // Takes `job` out if it still waits; true when it did.
  bool remove(const Job& job);
  // Takes out and returns the jobs whose deadline is before `now`.
  std::vector<std::shared_ptr<Job>> take_expired(Job::Clock::time_point now);
  // Gives every waiting job its position again, so that a change withheld from its streams
  // (Job::kQueuedInterval) reaches them even when the queue stops moving; called periodically.
  void retell_positions();
  // Takes out and returns every job of the line of `backend` (when the last worker of a kind is
  // gone).
  std::vector<std::shared_ptr<Job>> take_all(Backend backend);
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
  struct Running {
    const Job* job;
    Backend kind;
    Job::Clock::time_point expected_end;
    bool shared;  // taken from the shared line
  };

  Line& line(Backend backend) {
    return backend == Backend::kGpu ? gpu_ : backend == Backend::kCpu ? cpu_ : shared_;
  }
  // Gives each job of `line` its position; adds those whose streams should be told to `tell`,
  // for wake() once the mutex is released.
  void renumber(const Line& line, std::vector<std::shared_ptr<Job>>& tell);
  static void wake(const std::vector<std::shared_ptr<Job>>& tell);
  // The line and entry a free worker of `worker` takes next; null when none suits it.
  std::pair<Line*, Line::iterator> next_for(Backend worker);
  Line::iterator shared_job_for_cpu();
  // Seconds of work the GPU workers hold (queued in their line and left of what they run).
  double gpu_backlog(Job::Clock::time_point now) const;

  const size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Line gpu_, cpu_, shared_;
  std::vector<Running> running_;
  RunTimeModel model_;
  int gpu_workers_ = 0;
  int shared_cpu_limit_ = 0;
  uint64_t arrivals_ = 0;
  bool closed_ = false;
};

}  // namespace meshd
