// Where the queue sends jobs: the run-time model it learns from the workers, and the shared
// line of BACKEND_AUTO jobs that a CPU worker takes only where it would finish first. Part of
// server_jobs_test, so that ThreadSanitizer runs it too.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "server/job_queue.h"
#include "server/run_time_model.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

// A job of about `nodes` nodes (the estimate the queue goes by) that may run on `backend`.
std::shared_ptr<Job> job_of(double nodes, Backend backend = Backend::kAuto, int priority = 0) {
  JobSpec spec = to_job_spec(disk_request(0.2));
  spec.estimated_nodes = nodes;
  spec.options.priority = priority;
  return std::make_shared<Job>("j" + std::to_string(nodes), std::move(spec), backend,
                               Job::Clock::time_point::max());
}

TEST(RunTimeModel, PriorsGrowWithSizeAndTheGpuWinsLargeJobs) {
  RunTimeModel model;
  EXPECT_LT(model.predict(Backend::kGpu, 1e3), model.predict(Backend::kGpu, 1e6));
  EXPECT_LT(model.predict(Backend::kCpu, 1e3), model.predict(Backend::kCpu, 1e6));
  EXPECT_LT(model.predict(Backend::kGpu, 1e5), model.predict(Backend::kCpu, 1e5));
}

TEST(RunTimeModel, MeasurementsCorrectTheirSizeAndLendToOthers) {
  RunTimeModel model;
  const double prior_small = model.predict(Backend::kCpu, 2000);
  const double prior_large = model.predict(Backend::kCpu, 1e6);
  model.observe(Backend::kCpu, 2000, 4 * prior_small);
  EXPECT_NEAR(model.predict(Backend::kCpu, 2000), 4 * prior_small, 1e-9);
  // The only measurement is lent to every size until that size has its own.
  EXPECT_NEAR(model.predict(Backend::kCpu, 1e6), 4 * prior_large, 1e-6);
  model.observe(Backend::kCpu, 1e6, prior_large);
  EXPECT_NEAR(model.predict(Backend::kCpu, 1e6), prior_large, 1e-6);
  // A moving average: one odd run moves the estimate, not all the way.
  model.observe(Backend::kCpu, 2000, prior_small);
  const double after = model.predict(Backend::kCpu, 2000);
  EXPECT_LT(after, 4 * prior_small);
  EXPECT_GT(after, 2 * prior_small);
  // The GPU's figures are its own.
  EXPECT_NEAR(model.predict(Backend::kGpu, 2000), RunTimeModel().predict(Backend::kGpu, 2000),
              1e-12);
}

// One GPU worker at 10 ms and CPU workers at 75 ms per 2,000-node job: a free CPU worker takes
// the first shared job that the GPU would not finish within 75 ms, the 8th (the GPU would start
// it after 7 x 10 ms and finish at 80 ms).
TEST(JobQueue, CpuWorkerTakesTheFirstSharedJobItFinishesFirst) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  queue.observe_run(Backend::kGpu, 2000, 0.010);
  queue.observe_run(Backend::kCpu, 2000, 0.075);
  std::vector<std::shared_ptr<Job>> jobs;
  for (int i = 0; i < 12; ++i) {
    jobs.push_back(job_of(2000 + i));  // distinct ids, the same size class
    queue.push(jobs.back());
  }
  EXPECT_EQ(queue.pop(Backend::kCpu), jobs[7]);
  EXPECT_EQ(queue.pop(Backend::kGpu), jobs[0]);
  EXPECT_EQ(jobs[8]->info().queue_position(), 6);
  queue.close();
}

TEST(JobQueue, LargeSharedJobWaitsForTheGpu) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  auto large = job_of(1e6), cpu_only = job_of(1e6, Backend::kCpu);
  queue.push(large);
  queue.push(cpu_only);
  // The CPU worker passes over the large shared job (seconds on the CPU, under one on the GPU)
  // to the job that only it may run.
  EXPECT_EQ(queue.pop(Backend::kCpu), cpu_only);
  EXPECT_EQ(queue.pop(Backend::kGpu), large);
  queue.close();
}

TEST(JobQueue, OwnLineAndSharedLineInterleaveByPriority) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  auto shared_low = job_of(2000, Backend::kAuto, 0), gpu_high = job_of(2001, Backend::kGpu, 5);
  auto shared_high = job_of(2002, Backend::kAuto, 9);
  for (auto& j : {shared_low, gpu_high, shared_high}) queue.push(j);
  EXPECT_EQ(queue.pop(Backend::kGpu), shared_high);
  EXPECT_EQ(queue.pop(Backend::kGpu), gpu_high);
  EXPECT_EQ(queue.pop(Backend::kGpu), shared_low);
  queue.close();
}

// With no GPU worker left, a CPU worker waiting on a shared job it declined takes it.
TEST(JobQueue, SharedJobsFallToTheCpuWhenTheLastGpuWorkerGoes) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  auto large = job_of(1e6);
  queue.push(large);
  std::shared_ptr<Job> taken;
  std::thread cpu([&] { taken = queue.pop(Backend::kCpu); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  queue.set_gpu_workers(0);
  cpu.join();
  EXPECT_EQ(taken, large);
  queue.close();
}

// A CPU worker that declined a shared job takes it once the GPU's backlog grows past it: the
// decision is revisited on every push and every finished job.
TEST(JobQueue, DeclinedSharedJobIsTakenWhenTheGpuFallsBehind) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  queue.observe_run(Backend::kGpu, 2000, 0.010);
  queue.observe_run(Backend::kCpu, 2000, 0.015);
  auto first = job_of(2000);
  queue.push(first);
  std::shared_ptr<Job> taken;
  std::thread cpu([&] { taken = queue.pop(Backend::kCpu); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  auto second = job_of(2001);
  queue.push(second);  // 10 ms of GPU work ahead of it: 20 ms there, 15 on the CPU
  cpu.join();
  EXPECT_EQ(taken, second);
  EXPECT_EQ(queue.pop(Backend::kGpu), first);
  queue.close();
}

// The shared jobs that CPU workers run at once stop at the limit while a GPU worker takes jobs;
// one that ends makes room, and the CPU's own line is never held back.
TEST(JobQueue, CpuWorkersRunNoMoreSharedJobsThanTheLimit) {
  JobQueue queue(64);
  queue.set_gpu_workers(1);
  queue.set_shared_cpu_limit(1);
  queue.observe_run(Backend::kGpu, 2000, 0.010);
  queue.observe_run(Backend::kCpu, 2000, 0.001);  // every shared job finishes first on the CPU
  auto first = job_of(2000), second = job_of(2001), cpu_only = job_of(2002, Backend::kCpu);
  queue.push(first);
  queue.push(second);
  EXPECT_EQ(queue.pop(Backend::kCpu), first);
  queue.push(cpu_only);
  EXPECT_EQ(queue.pop(Backend::kCpu), cpu_only);  // at the limit, its own line still goes
  std::shared_ptr<Job> taken;
  std::atomic<bool> returned{false};
  std::thread cpu([&] {
    taken = queue.pop(Backend::kCpu);
    returned = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(returned.load());  // the second shared job waits for the first
  queue.done(*first, Backend::kCpu, 0.001, true);
  cpu.join();
  EXPECT_EQ(taken, second);
  queue.close();
}

}  // namespace
}  // namespace meshd::testing
