#include "server/job_queue.h"

#include <string>
#include <utility>

#include "core/common/error.h"

namespace meshd {

void JobQueue::renumber(const Line& l) {
  int position = 0;
  for (const Entry& e : l) e.job->set_queue_position(position++);
}

void JobQueue::push(std::shared_ptr<Job> job) {
  std::lock_guard lock(mutex_);
  if (closed_) throw Error(ErrorCode::kUnavailable, "", "the server is shutting down");
  if (gpu_.size() + cpu_.size() >= capacity_) {
    throw Error(ErrorCode::kUnavailable, "",
                "the job queue is full (" + std::to_string(capacity_) + " jobs); retry later");
  }
  Line& l = line(job->worker());
  l.insert(Entry{job->spec().options.priority, arrivals_++, std::move(job)});
  renumber(l);
  ready_.notify_all();
}

std::shared_ptr<Job> JobQueue::pop(Backend worker) {
  std::unique_lock lock(mutex_);
  Line& l = line(worker);
  ready_.wait(lock, [&] { return closed_ || !l.empty(); });
  if (closed_) return nullptr;
  std::shared_ptr<Job> job = l.begin()->job;
  l.erase(l.begin());
  renumber(l);
  return job;
}

bool JobQueue::remove(const Job& job) {
  std::lock_guard lock(mutex_);
  Line& l = line(job.worker());
  for (auto it = l.begin(); it != l.end(); ++it) {
    if (it->job.get() == &job) {
      l.erase(it);
      renumber(l);
      return true;
    }
  }
  return false;
}

std::vector<std::shared_ptr<Job>> JobQueue::take_expired(Job::Clock::time_point now) {
  std::vector<std::shared_ptr<Job>> out;
  std::lock_guard lock(mutex_);
  for (Line* l : {&gpu_, &cpu_}) {
    const size_t before = out.size();
    for (auto it = l->begin(); it != l->end();) {
      if (it->job->deadline() < now) {
        out.push_back(it->job);
        it = l->erase(it);
      } else {
        ++it;
      }
    }
    if (out.size() != before) renumber(*l);
  }
  return out;
}

std::vector<std::shared_ptr<Job>> JobQueue::take_all(Backend worker) {
  std::vector<std::shared_ptr<Job>> out;
  std::lock_guard lock(mutex_);
  Line& l = line(worker);
  for (const Entry& e : l) out.push_back(e.job);
  l.clear();
  return out;
}

std::vector<std::shared_ptr<Job>> JobQueue::close() {
  std::vector<std::shared_ptr<Job>> out;
  std::lock_guard lock(mutex_);
  closed_ = true;
  for (Line* l : {&gpu_, &cpu_}) {
    for (const Entry& e : *l) out.push_back(e.job);
    l->clear();
  }
  ready_.notify_all();
  return out;
}

size_t JobQueue::size() const {
  std::lock_guard lock(mutex_);
  return gpu_.size() + cpu_.size();
}

}  // namespace meshd
