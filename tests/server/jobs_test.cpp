// The job machinery without gRPC: the queue's order, limits and positions; a job's event state
// read by concurrent streams while a worker writes it; the manager under concurrent submits
// and cancels. Run under ThreadSanitizer by scripts/sanitize.sh tsan.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <random>
#include <stdexcept>
#include <thread>

#include "core/common/error.h"
#include "server/job_manager.h"
#include "tests/server/test_engines.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

using namespace std::chrono_literals;

std::shared_ptr<Job> make_job(int id, int priority = 0, Backend worker = Backend::kCpu,
                              Job::Clock::time_point deadline = Job::Clock::time_point::max()) {
  JobSpec spec = to_job_spec(disk_request(0.2));
  spec.options.priority = priority;
  return std::make_shared<Job>("j" + std::to_string(id), std::move(spec), worker, deadline);
}

TEST(JobQueue, OrdersByPriorityThenArrivalAndTellsPositions) {
  JobQueue queue(10);
  auto a = make_job(1, 0), b = make_job(2, 5), c = make_job(3, 0),
       g = make_job(4, 0, Backend::kGpu);
  for (auto& j : {a, b, c, g}) queue.push(j);
  EXPECT_EQ(b->info().queue_position(), 0);
  EXPECT_EQ(a->info().queue_position(), 1);
  EXPECT_EQ(c->info().queue_position(), 2);
  EXPECT_EQ(g->info().queue_position(), 0);  // its own line
  EXPECT_EQ(queue.pop(Backend::kCpu), b);
  EXPECT_EQ(a->info().queue_position(), 0);
  EXPECT_TRUE(queue.remove(*a));
  EXPECT_FALSE(queue.remove(*a));
  EXPECT_EQ(c->info().queue_position(), 0);
  EXPECT_EQ(queue.pop(Backend::kCpu), c);
  EXPECT_EQ(queue.pop(Backend::kGpu), g);
  EXPECT_EQ(queue.size(), 0u);
}

TEST(JobQueue, FullOrClosedQueueRefusesAtOnce) {
  JobQueue queue(2);
  queue.push(make_job(1));
  queue.push(make_job(2, 0, Backend::kGpu));
  try {
    queue.push(make_job(3));
    FAIL() << "a third job fit";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kUnavailable);
  }
  std::thread waiter([&] {
    EXPECT_NE(queue.pop(Backend::kCpu), nullptr);
    EXPECT_EQ(queue.pop(Backend::kCpu), nullptr);  // woken by close
  });
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(queue.close().size(), 1u);  // the GPU job was still waiting
  waiter.join();
  EXPECT_THROW(queue.push(make_job(4)), Error);
}

TEST(JobQueue, TakesExpiredJobs) {
  JobQueue queue(10);
  const auto now = Job::Clock::now();
  auto late = make_job(1, 0, Backend::kCpu, now - 1ms);
  auto fine = make_job(2, 0, Backend::kCpu, now + 1h);
  queue.push(late);
  queue.push(fine);
  const auto expired = queue.take_expired(now);
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_EQ(expired[0], late);
  EXPECT_EQ(fine->info().queue_position(), 0);
}

// Producers, consumers and removers at once: every job leaves the queue exactly once.
TEST(JobQueue, ConcurrentPushPopRemoveLosesNothing) {
  constexpr int kProducers = 4, kPerProducer = 200;
  JobQueue queue(64);
  std::atomic<int> popped{0}, removed{0}, refused{0};
  std::vector<std::shared_ptr<Job>> all(kProducers * kPerProducer);
  for (size_t i = 0; i < all.size(); ++i) all[i] = make_job(static_cast<int>(i), i % 3);
  std::vector<std::thread> threads;
  for (int c = 0; c < 2; ++c) {
    threads.emplace_back([&] {
      while (queue.pop(Backend::kCpu)) ++popped;
    });
  }
  std::vector<std::thread> producers;
  for (int p = 0; p < kProducers; ++p) {
    producers.emplace_back([&, p] {
      std::mt19937 rng(p);
      for (int i = 0; i < kPerProducer; ++i) {
        auto& job = all[p * kPerProducer + i];
        try {
          queue.push(job);
        } catch (const Error&) {
          ++refused;
          continue;
        }
        if (rng() % 4 == 0 && queue.remove(*job)) ++removed;
      }
    });
  }
  for (auto& t : producers) t.join();
  while (queue.size() > 0) std::this_thread::sleep_for(1ms);
  const size_t left = queue.close().size();
  for (auto& t : threads) t.join();
  EXPECT_EQ(popped + removed + refused + static_cast<int>(left), kProducers * kPerProducer);
}

// A queued job's streams hear of its position at first, then of a change at least
// kQueuedInterval after the last they heard of; info() has every change at once.
TEST(JobEvents, QueuePositionsAreToldAtMostEveryInterval) {
  auto job = make_job(1);
  const auto t0 = Job::Clock::now();
  EventCursor cursor;
  v1::MeshEvent event;
  grpc::Status status;
  EXPECT_TRUE(job->set_queue_position(2, t0));
  ASSERT_EQ(job->next_event(cursor, event, status), NextEvent::kEvent);
  EXPECT_EQ(event.queued().position(), 2);
  EXPECT_FALSE(job->set_queue_position(1, t0 + Job::kQueuedInterval / 2));
  EXPECT_EQ(job->info().queue_position(), 1);
  EXPECT_EQ(job->next_event(cursor, event, status), NextEvent::kNone);
  // The same position once the interval passed: the withheld change is told now.
  EXPECT_TRUE(job->set_queue_position(1, t0 + 2 * Job::kQueuedInterval));
  ASSERT_EQ(job->next_event(cursor, event, status), NextEvent::kEvent);
  EXPECT_EQ(event.queued().position(), 1);
  EXPECT_FALSE(job->set_queue_position(1, t0 + 4 * Job::kQueuedInterval));  // told already
  EXPECT_TRUE(job->set_queue_position(0, t0 + 4 * Job::kQueuedInterval));
  ASSERT_EQ(job->next_event(cursor, event, status), NextEvent::kEvent);
  EXPECT_EQ(event.queued().position(), 0);
  EXPECT_EQ(job->next_event(cursor, event, status), NextEvent::kNone);
}

// A queue that stops moving still tells a stream the position withheld from it: retell.
TEST(JobEvents, AStalledQueueRetellsWithheldPositions) {
  JobQueue queue(10);
  auto first = make_job(1), second = make_job(2);
  queue.push(first);
  queue.push(second);
  EventCursor cursor;
  v1::MeshEvent event;
  grpc::Status status;
  ASSERT_EQ(second->next_event(cursor, event, status), NextEvent::kEvent);
  EXPECT_EQ(event.queued().position(), 1);
  EXPECT_TRUE(queue.remove(*first));  // within the interval: withheld
  EXPECT_EQ(second->info().queue_position(), 0);
  EXPECT_EQ(second->next_event(cursor, event, status), NextEvent::kNone);
  std::this_thread::sleep_for(Job::kQueuedInterval + 10ms);
  queue.retell_positions();
  ASSERT_EQ(second->next_event(cursor, event, status), NextEvent::kEvent);
  EXPECT_EQ(event.queued().position(), 0);
}

// A worker publishes while three readers pull at their own pace: each reader sees queued, then
// started, then non-decreasing progress, then every chunk once and done.
// What one reader gets until nothing is new: the kind of each event, and whether it finished.
std::vector<std::string> read_events(const Job& job, EventCursor& cursor, bool& finished) {
  std::vector<std::string> kinds;
  v1::MeshEvent event;
  grpc::Status status;
  finished = false;
  for (NextEvent next; (next = job.next_event(cursor, event, status)) != NextEvent::kNone;) {
    if (next == NextEvent::kFinished) {
      finished = true;
      break;
    }
    if (event.has_result_chunk())
      kinds.push_back("chunk " + event.result_chunk().data());
    else if (event.has_done())
      kinds.push_back("done " + event.done().result_sha256());
    else
      kinds.push_back(event.has_queued() ? "queued" : event.has_started() ? "started" : "other");
  }
  return kinds;
}

TEST(JobEvents, APublishedPayloadsChunksGoOutBeforeTheDone) {
  auto job = make_job(1);
  job->set_queue_position(0, Job::Clock::now());
  ASSERT_TRUE(job->start(v1::Started()));
  auto payload = std::make_shared<ResultPayload>(ResultPayload{"abcde", 2});
  job->publish_payload(payload);
  EventCursor cursor;
  bool finished = false;
  EXPECT_EQ(read_events(*job, cursor, finished),
            (std::vector<std::string>{"queued", "started", "chunk ab", "chunk cd", "chunk e"}));
  EXPECT_FALSE(finished);  // no done before succeed
  EXPECT_EQ(job->state(), JobState::kRunning);
  EncodedResult result;
  result.payload = payload;
  result.done.set_result_sha256("sum");
  job->succeed(std::move(result));
  EXPECT_EQ(read_events(*job, cursor, finished), (std::vector<std::string>{"done sum"}));
  EXPECT_TRUE(finished);
  // A reader that comes later gets the same chunks, then the done.
  EventCursor late;
  EXPECT_EQ(read_events(*job, late, finished),
            (std::vector<std::string>{"queued", "started", "chunk ab", "chunk cd", "chunk e",
                                      "done sum"}));
}

TEST(JobEvents, ReadersSeeAConsistentStreamWhileTheWorkerWrites) {
  auto job = make_job(1);
  job->set_queue_position(0, Job::Clock::now());
  auto reader = [&](int pause_us, std::vector<std::string>& kinds) {
    EventCursor cursor;
    v1::MeshEvent event;
    grpc::Status status;
    int last_iteration = -1;
    size_t chunks = 0;
    for (;;) {
      const NextEvent next = job->next_event(cursor, event, status);
      if (next == NextEvent::kFinished) break;
      if (next == NextEvent::kNone) {
        std::this_thread::sleep_for(std::chrono::microseconds(50));
        continue;
      }
      if (event.has_progress()) {
        EXPECT_GE(event.progress().iteration(), last_iteration);
        last_iteration = event.progress().iteration();
      }
      if (event.has_result_chunk()) {
        EXPECT_EQ(event.result_chunk().index(), chunks++);
      }
      const std::string kind = event.has_queued()         ? "queued"
                               : event.has_started()      ? "started"
                               : event.has_result_chunk() ? "chunk"
                               : event.has_done()         ? "done"
                                                          : "running";
      if (kinds.empty() || kinds.back() != kind) kinds.push_back(kind);
      std::this_thread::sleep_for(std::chrono::microseconds(pause_us));
    }
    EXPECT_TRUE(status.ok());
    EXPECT_EQ(chunks, 3u);
  };
  std::vector<std::string> k1, k2, k3;
  std::thread r1(reader, 0, std::ref(k1)), r2(reader, 100, std::ref(k2)),
      r3(reader, 1000, std::ref(k3));
  v1::Started started;
  ASSERT_TRUE(job->start(started));
  std::vector<Vec2> points(100, Vec2{0.5, 0.5});
  std::vector<std::array<int32_t, 3>> triangles(50, {0, 1, 2});
  for (int i = 1; i <= 2000; ++i) {
    v1::Progress p;
    p.set_iteration(i);
    job->publish_progress(p);
    if (i % 10 == 0) job->publish_snapshot(i, points, i % 100 == 0 ? &triangles : nullptr);
  }
  EncodedResult result;
  result.payload = std::make_shared<ResultPayload>(ResultPayload{"abc", 1});
  job->succeed(std::move(result));
  r1.join();
  r2.join();
  r3.join();
  for (const auto* kinds : {&k1, &k2, &k3}) {
    ASSERT_GE(kinds->size(), 4u);
    EXPECT_EQ(kinds->front(), "queued");
    EXPECT_EQ((*kinds)[1], "started");
    EXPECT_EQ(kinds->back(), "done");
    EXPECT_EQ((*kinds)[kinds->size() - 2], "chunk");
  }
}

// Many clients submit and cancel at once on two workers: every job ends in a final state,
// nothing stays live, and the counts add up.
TEST(JobManager, ConcurrentSubmitsAndCancelsAllEnd) {
  Metrics metrics;
  JobManagerOptions options;
  options.queue_capacity = 1000;
  JobManager manager(options, cpu_workers(2), metrics);
  manager.start();
  constexpr int kClients = 4, kJobs = 25;
  std::vector<std::shared_ptr<Job>> jobs(kClients * kJobs);
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      std::mt19937 rng(c);
      for (int i = 0; i < kJobs; ++i) {
        auto job =
            manager.submit(disk_request(0.1 + 0.05 * (rng() % 3)), Job::Clock::time_point::max());
        jobs[c * kJobs + i] = job;
        if (rng() % 3 == 0) {
          manager.cancel(job->id(), grpc::Status(grpc::StatusCode::CANCELLED, "test"));
        }
      }
    });
  }
  for (auto& t : clients) t.join();
  const auto until = Job::Clock::now() + 60s;
  while (manager.live_jobs() > 0 && Job::Clock::now() < until) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(manager.live_jobs(), 0);
  int succeeded = 0, cancelled = 0;
  for (const auto& job : jobs) {
    ASSERT_TRUE(job->is_final()) << job->id();
    // Run or cancelled in the queue, a finished job no longer holds its compiled geometry.
    EXPECT_TRUE(job->spec().plane.geometry.code.empty()) << job->id();
    succeeded += job->state() == JobState::kSucceeded;
    cancelled += job->state() == JobState::kCancelled;
  }
  EXPECT_EQ(succeeded + cancelled, kClients * kJobs);
  EXPECT_GT(cancelled, 0);
  EXPECT_EQ(static_cast<int>(manager.list(v1::JOB_STATE_UNSPECIFIED).size()), kClients * kJobs);
  const std::string text = metrics.text();
  EXPECT_NE(text.find("meshd_jobs_total{outcome=\"succeeded\"} " + std::to_string(succeeded)),
            std::string::npos);
  manager.drain(0ms);
}

TEST(JobManager, AFinishedVolumeKeepsNoGeometry) {
  Metrics metrics;
  JobManager manager(JobManagerOptions{}, cpu_workers(1), metrics);
  manager.start();
  v1::MeshRequest request;
  request.mutable_volume()->mutable_geometry()->mutable_sphere()->set_radius(1.0);
  request.set_h0(0.4);
  const std::shared_ptr<Job> job = manager.submit(request, Job::Clock::time_point::max());
  const auto until = Job::Clock::now() + 30s;
  while (manager.live_jobs() > 0 && Job::Clock::now() < until) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(job->state(), JobState::kSucceeded);
  ASSERT_TRUE(job->spec().volume.has_value());
  EXPECT_EQ(job->spec().volume->geometry, nullptr);
  EXPECT_GT(job->spec().estimated_nodes, 0.0);  // what GetJob shows stays
  manager.drain(0ms);
}

TEST(JobManager, RetentionForgetsFinishedJobs) {
  Metrics metrics;
  JobManagerOptions options;
  options.retention = 50ms;
  JobManager manager(options, cpu_workers(1), metrics);
  manager.start();
  const std::string id = manager.submit(disk_request(0.2), Job::Clock::time_point::max())->id();
  const auto until = Job::Clock::now() + 10s;
  bool forgotten = false;
  while (!forgotten && Job::Clock::now() < until) {
    try {
      manager.find(id);
      std::this_thread::sleep_for(5ms);
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kNotFound);
      forgotten = true;
    }
  }
  EXPECT_TRUE(forgotten);
  manager.drain(0ms);
}

// A worker warms up on the thread that runs its jobs, so that the first job finds that thread's
// heap and state warm.
TEST(JobManager, AWorkerWarmsUpOnTheThreadThatRunsItsJobs) {
  Metrics metrics;
  auto threads = std::make_shared<ThreadLog>();
  JobManager manager(JobManagerOptions{},
                     {{"cpu0", Backend::kCpu, thread_logging_cpu_factory(threads)}}, metrics);
  manager.start();
  const auto job = manager.submit(disk_request(0.2), Job::Clock::time_point::max());
  const auto until = Job::Clock::now() + 10s;
  while (!job->is_final() && Job::Clock::now() < until) std::this_thread::sleep_for(5ms);
  ASSERT_EQ(job->state(), JobState::kSucceeded);
  manager.drain(0ms);
  std::lock_guard lock(threads->mutex);
  ASSERT_EQ(threads->ids.size(), 2u);  // the warm-up, then the job
  EXPECT_EQ(threads->ids[0], threads->ids[1]);
  EXPECT_NE(threads->ids[0], std::this_thread::get_id());
}

// Workers warm up at once; one that cannot build its engine fails the start, and the manager
// still ends (the warm workers' threads with it).
TEST(JobManager, AWorkerThatCannotWarmUpFailsTheStart) {
  Metrics metrics;
  std::vector<WorkerSpec> workers = cpu_workers(2, 1);
  workers.push_back({"broken", Backend::kCpu, []() -> std::unique_ptr<WorkerEngine> {
                       throw std::runtime_error("no engine here");
                     }});
  JobManager manager(JobManagerOptions{}, std::move(workers), metrics);
  EXPECT_THROW(manager.start(), std::runtime_error);
  manager.drain(0ms);
}

}  // namespace
}  // namespace meshd::testing
