#include "server/job_queue.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/common/error.h"

namespace meshd {

namespace {

double seconds_between(Job::Clock::time_point from, Job::Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

}  // namespace

void JobQueue::renumber(const Line& l, std::vector<std::shared_ptr<Job>>& tell) {
  const auto now = Job::Clock::now();
  int position = 0;
  for (const Entry& e : l) {
    if (e.job->set_queue_position(position++, now)) tell.push_back(e.job);
  }
}

void JobQueue::wake(const std::vector<std::shared_ptr<Job>>& tell) {
  for (const auto& job : tell) job->wake_subscribers();
}

void JobQueue::set_gpu_workers(int count) {
  std::lock_guard lock(mutex_);
  gpu_workers_ = count;
  changed_.notify_all();
}

void JobQueue::set_shared_cpu_limit(int jobs) {
  std::lock_guard lock(mutex_);
  shared_cpu_limit_ = jobs;
  changed_.notify_all();
}

void JobQueue::push(std::shared_ptr<Job> job) {
  std::vector<std::shared_ptr<Job>> tell;
  {
    std::lock_guard lock(mutex_);
    if (closed_) throw Error(ErrorCode::kUnavailable, "", "the server is shutting down");
    if (gpu_.size() + cpu_.size() + shared_.size() >= capacity_) {
      throw Error(ErrorCode::kUnavailable, "",
                  "the job queue is full (" + std::to_string(capacity_) + " jobs); retry later");
    }
    Line& l = line(job->backend());
    l.insert(Entry{job->spec().options.priority, arrivals_++, std::move(job)});
    renumber(l, tell);
    changed_.notify_all();
  }
  wake(tell);
}

double JobQueue::gpu_backlog(Job::Clock::time_point now) const {
  double seconds = 0;
  for (const Entry& e : gpu_)
    seconds += model_.predict(Backend::kGpu, e.job->spec().estimated_nodes);
  for (const Running& r : running_) {
    if (r.kind == Backend::kGpu) seconds += std::max(0.0, seconds_between(now, r.expected_end));
  }
  return seconds;
}

JobQueue::Line::iterator JobQueue::shared_job_for_cpu() {
  if (gpu_workers_ == 0) return shared_.begin();
  const auto shared_on_cpu = std::count_if(running_.begin(), running_.end(), [](const Running& r) {
    return r.kind == Backend::kCpu && r.shared;
  });
  if (shared_cpu_limit_ > 0 && shared_on_cpu >= shared_cpu_limit_) return shared_.end();
  // The GPU workers share their backlog; a shared job behind others waits for those too.
  double gpu_work = gpu_backlog(Job::Clock::now());
  for (auto it = shared_.begin(); it != shared_.end(); ++it) {
    const double nodes = it->job->spec().estimated_nodes;
    const double on_gpu = model_.predict(Backend::kGpu, nodes);
    if (model_.predict(Backend::kCpu, nodes) < gpu_work / gpu_workers_ + on_gpu) return it;
    gpu_work += on_gpu;
  }
  return shared_.end();
}

std::pair<JobQueue::Line*, JobQueue::Line::iterator> JobQueue::next_for(Backend worker) {
  Line& own = line(worker);
  const auto shared = worker == Backend::kGpu ? shared_.begin() : shared_job_for_cpu();
  const bool has_own = !own.empty(), has_shared = shared != shared_.end();
  if (has_own && (!has_shared || *own.begin() < *shared)) return {&own, own.begin()};
  if (has_shared) return {&shared_, shared};
  return {nullptr, {}};
}

std::shared_ptr<Job> JobQueue::pop(Backend worker) {
  std::unique_lock lock(mutex_);
  std::pair<Line*, Line::iterator> next{nullptr, {}};
  // Woken by every change that can make a job suit this worker: a push, a worker count, a job
  // done (its GPU time no longer ahead, or its place among the shared CPU jobs free). Time alone
  // only shortens the GPU backlog, which never turns a CPU worker's no into a yes.
  changed_.wait(lock, [&] {
    if (closed_) return true;
    next = next_for(worker);
    return next.first != nullptr;
  });
  if (closed_) return nullptr;
  auto [l, it] = next;
  std::shared_ptr<Job> job = it->job;
  l->erase(it);
  std::vector<std::shared_ptr<Job>> tell;
  renumber(*l, tell);
  const double expected = model_.predict(worker, job->spec().estimated_nodes);
  running_.push_back(Running{job.get(), worker,
                             Job::Clock::now() + std::chrono::duration_cast<Job::Clock::duration>(
                                                     std::chrono::duration<double>(expected)),
                             l == &shared_});
  lock.unlock();
  wake(tell);
  return job;
}

void JobQueue::done(const Job& job, Backend kind, double seconds, bool succeeded) {
  std::lock_guard lock(mutex_);
  std::erase_if(running_, [&](const Running& r) { return r.job == &job; });
  // The model predicts plane jobs; a volume's seconds per node are another scale.
  if (succeeded && !job.spec().volume) model_.observe(kind, job.spec().estimated_nodes, seconds);
  changed_.notify_all();
}

void JobQueue::observe_run(Backend kind, double nodes, double seconds) {
  std::lock_guard lock(mutex_);
  model_.observe(kind, nodes, seconds);
}

bool JobQueue::remove(const Job& job) {
  std::vector<std::shared_ptr<Job>> tell;
  {
    std::lock_guard lock(mutex_);
    Line& l = line(job.backend());
    const auto it =
        std::find_if(l.begin(), l.end(), [&](const Entry& e) { return e.job.get() == &job; });
    if (it == l.end()) return false;
    l.erase(it);
    renumber(l, tell);
  }
  wake(tell);
  return true;
}

std::vector<std::shared_ptr<Job>> JobQueue::take_expired(Job::Clock::time_point now) {
  std::vector<std::shared_ptr<Job>> out, tell;
  {
    std::lock_guard lock(mutex_);
    for (Line* l : {&gpu_, &cpu_, &shared_}) {
      const size_t before = out.size();
      for (auto it = l->begin(); it != l->end();) {
        if (it->job->deadline() < now) {
          out.push_back(it->job);
          it = l->erase(it);
        } else {
          ++it;
        }
      }
      if (out.size() != before) renumber(*l, tell);
    }
  }
  wake(tell);
  return out;
}

void JobQueue::retell_positions() {
  std::vector<std::shared_ptr<Job>> tell;
  {
    std::lock_guard lock(mutex_);
    for (const Line* l : {&gpu_, &cpu_, &shared_}) renumber(*l, tell);
  }
  wake(tell);
}

std::vector<std::shared_ptr<Job>> JobQueue::take_all(Backend backend) {
  std::vector<std::shared_ptr<Job>> out;
  std::lock_guard lock(mutex_);
  Line& l = line(backend);
  for (const Entry& e : l) out.push_back(e.job);
  l.clear();
  return out;
}

std::vector<std::shared_ptr<Job>> JobQueue::close() {
  std::vector<std::shared_ptr<Job>> out;
  std::lock_guard lock(mutex_);
  closed_ = true;
  for (Line* l : {&gpu_, &cpu_, &shared_}) {
    for (const Entry& e : *l) out.push_back(e.job);
    l->clear();
  }
  changed_.notify_all();
  return out;
}

size_t JobQueue::size() const {
  std::lock_guard lock(mutex_);
  return gpu_.size() + cpu_.size() + shared_.size();
}

}  // namespace meshd
