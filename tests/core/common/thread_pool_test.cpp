// ThreadPool::for_chunks: every index exactly once, chunk numbering, and reductions by chunk
// that give the same bits for any number of threads.
#include "core/common/thread_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace meshd {
namespace {

TEST(ThreadPool, SizeCountsTheCallingThread) {
  EXPECT_EQ(ThreadPool(1).size(), 1u);
  EXPECT_EQ(ThreadPool(3).size(), 3u);
  EXPECT_GE(ThreadPool().size(), 1u);
  EXPECT_EQ(ThreadPool::chunk_count(0, 8), 0u);
  EXPECT_EQ(ThreadPool::chunk_count(8, 8), 1u);
  EXPECT_EQ(ThreadPool::chunk_count(9, 8), 2u);
  EXPECT_EQ(ThreadPool::chunk_count(10, 3), 4u);
}

TEST(ThreadPool, EveryIndexVisitedOnceWithConsistentChunks) {
  for (unsigned threads : {1u, 2u, 4u}) {
    ThreadPool pool(threads);
    for (size_t n : {size_t{0}, size_t{1}, size_t{5}, size_t{64}, size_t{1000}, size_t{12345}}) {
      for (size_t chunk : {size_t{1}, size_t{7}, size_t{64}, size_t{5000}}) {
        std::vector<std::atomic<int>> visits(n);
        std::vector<std::atomic<int>> chunk_calls(ThreadPool::chunk_count(n, chunk));
        std::atomic<int> bad{0};
        pool.for_chunks(n, chunk, [&](size_t c, size_t begin, size_t end) {
          if (c >= chunk_calls.size() || begin != c * chunk || end != std::min(n, begin + chunk) ||
              begin >= end) {
            ++bad;
            return;
          }
          ++chunk_calls[c];
          for (size_t i = begin; i < end; ++i) ++visits[i];
        });
        EXPECT_EQ(bad.load(), 0) << threads << " threads, n " << n << ", chunk " << chunk;
        for (size_t c = 0; c < chunk_calls.size(); ++c) ASSERT_EQ(chunk_calls[c].load(), 1) << c;
        for (size_t i = 0; i < n; ++i)
          ASSERT_EQ(visits[i].load(), 1) << threads << " threads, n " << n << ", index " << i;
      }
    }
  }
}

// Sum of terms of very different magnitudes and signs, where the order of additions shows in the
// last bits: partial sums per chunk, combined in chunk order.
double chunked_sum(ThreadPool& pool, size_t n, size_t chunk) {
  std::vector<double> partial(ThreadPool::chunk_count(n, chunk), 0.0);
  pool.for_chunks(n, chunk, [&](size_t c, size_t begin, size_t end) {
    double s = 0;
    for (size_t i = begin; i < end; ++i)
      s += std::sin(static_cast<double>(i)) * std::pow(10.0, static_cast<double>(i % 17) - 8);
    partial[c] = s;
  });
  double total = 0;
  for (double s : partial) total += s;
  return total;
}

TEST(ThreadPool, ChunkReductionsAreIdenticalForAnyThreadCount) {
  for (size_t n : {size_t{1000}, size_t{100000}}) {
    for (size_t chunk : {size_t{1}, size_t{100}, size_t{8192}}) {
      ThreadPool one(1);
      const double want = chunked_sum(one, n, chunk);
      for (unsigned threads : {2u, 3u, 8u}) {
        ThreadPool pool(threads);
        for (int rep = 0; rep < 5; ++rep) {
          const double got = chunked_sum(pool, n, chunk);
          EXPECT_EQ(got, want) << threads << " threads, n " << n << ", chunk " << chunk;
        }
      }
    }
  }
}

TEST(ThreadPool, ManyConsecutiveJobsOnOnePool) {
  // Back-to-back small jobs: no lost wake-up, no job seeing the previous one's range.
  ThreadPool pool(4);
  for (int job = 0; job < 2000; ++job) {
    const size_t n = 1 + static_cast<size_t>(job % 50);
    std::atomic<size_t> sum{0};
    pool.for_chunks(n, 3, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) sum += i + 1;
    });
    ASSERT_EQ(sum.load(), n * (n + 1) / 2) << "job " << job;
  }
}

TEST(ThreadPool, WorkIsSharedWhenThereAreManyChunks) {
  // The first chunk waits (up to 10 s) until some chunk runs on another thread: with a working
  // pool of 4 that happens at once; with workers that never wake it fails, not hangs.
  ThreadPool pool(4);
  std::mutex m;
  std::thread::id first_thread;
  bool first_set = false;
  std::atomic<bool> other_thread_ran{false};
  pool.for_chunks(64, 1, [&](size_t c, size_t, size_t) {
    const std::thread::id me = std::this_thread::get_id();
    {
      std::lock_guard lock(m);
      if (!first_set) {
        first_thread = me;
        first_set = true;
      } else if (me != first_thread) {
        other_thread_ran = true;
      }
    }
    if (c != 0) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!other_thread_ran && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  EXPECT_TRUE(other_thread_ran.load());
}

TEST(ThreadPool, CallersThatShareAPoolEachGetEveryIndexOnce) {
  // Eight threads loop on one pool of 4 at once (the service's admissions): a call made while
  // another runs takes its chunks on its own thread, and no call sees another's range.
  ThreadPool pool(4);
  std::vector<std::thread> callers;
  std::atomic<int> wrong{0};
  for (int t = 0; t < 8; ++t) {
    callers.emplace_back([&, t] {
      for (int job = 0; job < 200; ++job) {
        const size_t n = 50 + static_cast<size_t>((job * 7 + t) % 200);
        std::vector<std::atomic<int>> seen(n);
        pool.for_chunks(n, 4, [&](size_t, size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) ++seen[i];
        });
        for (const auto& s : seen)
          if (s.load() != 1) ++wrong;
      }
    });
  }
  for (auto& c : callers) c.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST(ThreadPool, ALoopInsideALoopOfTheSamePoolRunsOnItsCaller) {
  ThreadPool pool(3);
  std::atomic<size_t> sum{0};
  pool.for_chunks(8, 1, [&](size_t, size_t, size_t) {
    pool.for_chunks(10, 2, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) sum += i;
    });
  });
  EXPECT_EQ(sum.load(), 8u * 45u);
}

}  // namespace
}  // namespace meshd
