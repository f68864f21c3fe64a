#include "core/common/thread_pool.h"

#include <algorithm>

namespace meshd {

ThreadPool::ThreadPool(unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

void ThreadPool::run_chunks(std::unique_lock<std::mutex>& lock) {
  while (next_ < n_) {
    const size_t begin = next_;
    const size_t end = std::min(n_, begin + chunk_);
    next_ = end;
    const auto* job = job_;
    lock.unlock();
    (*job)(begin / chunk_, begin, end);
    lock.lock();
    if (--chunks_left_ == 0) done_.notify_all();
  }
}

void ThreadPool::worker_loop() {
  unsigned seen = 0;
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || (generation_ != seen && next_ < n_); });
    if (stop_) return;
    seen = generation_;
    run_chunks(lock);
  }
}

void ThreadPool::for_chunks(size_t n, size_t chunk,
                            const std::function<void(size_t, size_t, size_t)>& fn) {
  if (n == 0) return;
  const size_t chunks = chunk_count(n, chunk);
  if (workers_.empty() || chunks == 1) {
    for_chunks_in_order(n, chunk, fn);
    return;
  }
  std::unique_lock lock(mutex_);
  if (job_ != nullptr) {  // another caller's loop holds the workers
    lock.unlock();
    for_chunks_in_order(n, chunk, fn);
    return;
  }
  job_ = &fn;
  n_ = n;
  chunk_ = chunk;
  next_ = 0;
  chunks_left_ = chunks;
  ++generation_;
  wake_.notify_all();
  run_chunks(lock);
  done_.wait(lock, [&] { return chunks_left_ == 0; });
  job_ = nullptr;
}

void ThreadPool::for_chunks_in_order(size_t n, size_t chunk,
                                     const std::function<void(size_t, size_t, size_t)>& fn) {
  for (size_t c = 0; c < chunk_count(n, chunk); ++c) fn(c, c * chunk, std::min(n, (c + 1) * chunk));
}

void for_chunks(ThreadPool* pool, size_t n, size_t chunk,
                const std::function<void(size_t, size_t, size_t)>& fn) {
  if (pool != nullptr)
    pool->for_chunks(n, chunk, fn);
  else
    ThreadPool::for_chunks_in_order(n, chunk, fn);
}

}  // namespace meshd
