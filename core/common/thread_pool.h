// A small fixed pool of worker threads for data-parallel loops over index ranges.
//
// Work is cut into chunks of a fixed size, independent of the number of threads, so that a
// reduction that adds per-chunk partial results in chunk order gives the same bits on any
// machine: the CPU engine stays deterministic for a given request and seed.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace meshd {

class ThreadPool {
 public:
  // threads = 0: one per hardware thread.
  explicit ThreadPool(unsigned threads = 0);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()) + 1; }

  // Calls fn(chunk, begin, end) for consecutive chunks of [0, n) of `chunk` indices each, in
  // parallel; returns when all are done. Small ranges run on the caller's thread, and so do all
  // the chunks of a call made while another caller's loop runs: threads may share one pool.
  void for_chunks(size_t n, size_t chunk, const std::function<void(size_t, size_t, size_t)>& fn);

  static size_t chunk_count(size_t n, size_t chunk) { return (n + chunk - 1) / chunk; }
  // The same chunks in order on the caller's thread.
  static void for_chunks_in_order(size_t n, size_t chunk,
                                  const std::function<void(size_t, size_t, size_t)>& fn);

 private:
  void worker_loop();
  // Takes chunks until none are left; `lock` holds mutex_ on entry and on return.
  void run_chunks(std::unique_lock<std::mutex>& lock);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(size_t, size_t, size_t)>* job_ = nullptr;
  size_t n_ = 0, chunk_ = 1, next_ = 0, chunks_left_ = 0;
  unsigned generation_ = 0;
  bool stop_ = false;
};

// pool->for_chunks, or the same chunks in order on the caller's thread when there is no pool.
void for_chunks(ThreadPool* pool, size_t n, size_t chunk,
                const std::function<void(size_t, size_t, size_t)>& fn);

// Calls fn(begin, end, out) for consecutive chunks of [0, n) as for_chunks does, each chunk
// appending to its own list, and returns the lists joined in chunk order: the same result for
// any number of threads.
template <typename T, typename Fn>
std::vector<T> gather_chunks(ThreadPool* pool, size_t n, size_t chunk, Fn&& fn) {
  std::vector<std::vector<T>> found(ThreadPool::chunk_count(n, chunk));
  for_chunks(pool, n, chunk, [&](size_t c, size_t begin, size_t end) { fn(begin, end, found[c]); });
  size_t total = 0;
  for (const auto& f : found) total += f.size();
  std::vector<T> out;
  out.reserve(total);
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  return out;
}

}  // namespace meshd
