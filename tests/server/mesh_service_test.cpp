// meshd.v1.MeshService end to end on an in-process server over loopback: each RPC, the order of
// a stream's events, a result larger than a client's default 4 MiB message limit, every class
// of bad input, the queue limit, cancellation, deadlines, disconnection, engine failures.
#include <gtest/gtest.h>

#include <thread>

#include "tests/server/test_engines.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

using namespace std::chrono_literals;

v1::JobInfo get_job(v1::MeshService::Stub& stub, const std::string& id) {
  v1::JobRef ref;
  ref.set_job_id(id);
  v1::JobInfo info;
  auto context = context_with_deadline();
  EXPECT_TRUE(stub.GetJob(context.get(), ref, &info).ok());
  return info;
}

// Polls until the job reaches `state` or `timeout` passes.
v1::JobInfo wait_for_state(v1::MeshService::Stub& stub, const std::string& id, v1::JobState state,
                           std::chrono::milliseconds timeout = 10s) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  v1::JobInfo info;
  do {
    info = get_job(stub, id);
    if (info.state() == state) return info;
    std::this_thread::sleep_for(5ms);
  } while (std::chrono::steady_clock::now() < until);
  return info;
}

bool no_live_jobs(TestServer& server) {
  return eventually([&] { return server.server().jobs().live_jobs() == 0; });
}

std::string submit(v1::MeshService::Stub& stub, const v1::MeshRequest& request) {
  v1::JobRef ref;
  auto context = context_with_deadline();
  const grpc::Status s = stub.Submit(context.get(), request, &ref);
  EXPECT_TRUE(s.ok()) << s.error_message();
  return ref.job_id();
}

grpc::Status cancel(v1::MeshService::Stub& stub, const std::string& id) {
  v1::JobRef ref;
  ref.set_job_id(id);
  v1::JobInfo info;
  auto context = context_with_deadline();
  return stub.Cancel(context.get(), ref, &info);
}

StreamResult watch(v1::MeshService::Stub& stub, const std::string& id) {
  v1::JobRef ref;
  ref.set_job_id(id);
  auto context = context_with_deadline(60s);
  auto reader = stub.Watch(context.get(), ref);
  return read_stream(*reader);
}

// Checks the assembled mesh against its done event.
void expect_valid_result(const StreamResult& r) {
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  ASSERT_TRUE(r.has_done);
  EXPECT_TRUE(r.checksum_ok);
  EXPECT_EQ(r.mesh.points_size(), 2 * r.done.nodes());
  EXPECT_EQ(r.mesh.triangles_size(), 3 * r.done.triangles());
  EXPECT_EQ(r.mesh.boundary_edges_size(), 2 * r.done.boundary_edges());
  for (int32_t v : r.mesh.triangles()) ASSERT_TRUE(v >= 0 && v < r.done.nodes());
  EXPECT_GE(r.done.quality().q_min(), 0.6);
  EXPECT_GE(r.done.quality().q_mean(), 0.97);
  EXPECT_TRUE(r.done.stats().converged());
}

TEST(MeshService, GenerateStreamsEventsInOrder) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest request = disk_request(0.04);  // ~2,300 nodes
  request.mutable_options()->set_snapshot_every(5);
  const StreamResult r = generate(*stub, request);
  expect_valid_result(r);
  EXPECT_NEAR(static_cast<double>(r.done.nodes()), 3.63 / (0.04 * 0.04), 0.1 * 2300);

  const auto kinds = r.kinds();
  ASSERT_GE(kinds.size(), 4u);
  EXPECT_EQ(kinds[0], "queued");
  EXPECT_EQ(kinds[1], "started");
  EXPECT_EQ(kinds.back(), "done");
  // After started: progress and snapshots, then only result chunks, then done.
  size_t i = 2;
  while (i < kinds.size() && (kinds[i] == "progress" || kinds[i] == "snapshot")) ++i;
  EXPECT_GT(i, 2u) << "no progress or snapshot before the result";
  ASSERT_LT(i, kinds.size());
  while (i < kinds.size() && kinds[i] == "result_chunk") ++i;
  EXPECT_EQ(i, kinds.size() - 1);

  // The first snapshot carries the triangles; snapshot iterations follow snapshot_every.
  bool first = true;
  for (const auto& e : r.events) {
    if (!e.has_snapshot()) continue;
    EXPECT_EQ(e.snapshot().iteration() % 5, 0);
    if (first) {
      EXPECT_TRUE(e.snapshot().has_triangles());
      EXPECT_GT(e.snapshot().triangles_size(), 0);
      first = false;
    }
    EXPECT_GT(e.snapshot().points_size(), 0);
  }
  EXPECT_FALSE(first) << "no snapshot streamed";
  EXPECT_EQ(r.events[1].started().backend(), v1::JobOptions::BACKEND_CPU);
  EXPECT_EQ(r.done.backend(), v1::JobOptions::BACKEND_CPU);
}

// A ~165k-node mesh (about 5 MB of result) through a client with gRPC's default 4 MiB limit.
TEST(MeshService, ResultLargerThanDefaultMessageLimitArrivesInChunks) {
  TestServer server(test_options(), cpu_workers(1, 0));
  auto stub = server.stub();
  const StreamResult r = generate(*stub, disk_request(0.0047), 300s);
  expect_valid_result(r);
  EXPECT_GT(r.done.result_bytes(), 4u << 20);
  int chunks = 0;
  for (const auto& e : r.events) {
    if (!e.has_result_chunk()) continue;
    EXPECT_EQ(e.result_chunk().index(), static_cast<uint32_t>(chunks));
    EXPECT_EQ(e.result_chunk().total_bytes(), r.done.result_bytes());
    ++chunks;
  }
  EXPECT_EQ(chunks, static_cast<int>((r.done.result_bytes() + (1 << 20) - 1) >> 20));
}

TEST(MeshService, SubmitWatchGetAndList) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest request = disk_request(0.1);
  request.mutable_options()->set_label("first");
  const std::string id = submit(*stub, request);
  ASSERT_FALSE(id.empty());
  const StreamResult live = watch(*stub, id);
  expect_valid_result(live);
  EXPECT_EQ(live.job_id, id);

  const v1::JobInfo info = get_job(*stub, id);
  EXPECT_EQ(info.state(), v1::JOB_STATE_SUCCEEDED);
  EXPECT_EQ(info.label(), "first");
  EXPECT_EQ(info.done().result_sha256(), live.done.result_sha256());
  EXPECT_EQ(info.nodes(), live.done.nodes());

  // Watching a finished job replays it from the start: the same result at once.
  const StreamResult again = watch(*stub, id);
  expect_valid_result(again);
  EXPECT_EQ(again.payload, live.payload);
  EXPECT_EQ(again.kinds().front(), "queued");

  const std::string second = submit(*stub, disk_request(0.1));
  ASSERT_EQ(wait_for_state(*stub, second, v1::JOB_STATE_SUCCEEDED).state(),
            v1::JOB_STATE_SUCCEEDED);
  v1::ListJobsRequest list_request;
  v1::ListJobsResponse list;
  auto context = context_with_deadline();
  ASSERT_TRUE(stub->ListJobs(context.get(), list_request, &list).ok());
  ASSERT_EQ(list.jobs_size(), 2);
  EXPECT_EQ(list.jobs(0).job_id(), id);  // in submission order
  EXPECT_EQ(list.jobs(1).job_id(), second);

  list_request.set_state(v1::JOB_STATE_RUNNING);
  context = context_with_deadline();
  ASSERT_TRUE(stub->ListJobs(context.get(), list_request, &list).ok());
  EXPECT_EQ(list.jobs_size(), 0);
}

TEST(MeshService, UnknownJobIsNotFound) {
  TestServer server;
  auto stub = server.stub();
  v1::JobRef ref;
  ref.set_job_id("j-nope");
  v1::JobInfo info;
  auto context = context_with_deadline();
  const grpc::Status s = stub->GetJob(context.get(), ref, &info);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_NE(s.error_message().find("job_id"), std::string::npos);
  EXPECT_EQ(watch(*stub, "j-nope").status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(cancel(*stub, "j-nope").error_code(), grpc::StatusCode::NOT_FOUND);
}

struct BadInput {
  const char* what;
  std::function<void(v1::MeshRequest&)> spoil;
  grpc::StatusCode code;
  const char* field;  // the message starts with this field path
};

TEST(MeshService, EveryBadInputClassGetsItsStatusAndFieldPath) {
  using C = grpc::StatusCode;
  const std::vector<BadInput> cases = {
      {"no geometry", [](auto& r) { r.clear_geometry(); }, C::INVALID_ARGUMENT, "geometry"},
      {"negative h0", [](auto& r) { r.set_h0(-1); }, C::INVALID_ARGUMENT, "h0"},
      {"NaN h0", [](auto& r) { r.set_h0(std::nan("")); }, C::INVALID_ARGUMENT, "h0"},
      {"zero radius", [](auto& r) { r.mutable_geometry()->mutable_circle()->set_radius(0); },
       C::INVALID_ARGUMENT, "geometry.circle.radius"},
      {"deltat out of range", [](auto& r) { r.mutable_params()->set_deltat(0.9); },
       C::INVALID_ARGUMENT, "params.deltat"},
      {"max_iterations 0", [](auto& r) { r.mutable_params()->set_max_iterations(0); },
       C::INVALID_ARGUMENT, "params.max_iterations"},
      {"fixed point outside",
       [](auto& r) {
         auto* p = r.add_fixed_points();
         p->set_x(5);
         p->set_y(0);
       },
       C::INVALID_ARGUMENT, "fixed_points[0]"},
      {"priority 11", [](auto& r) { r.mutable_options()->set_priority(11); }, C::INVALID_ARGUMENT,
       "options.priority"},
      {"unknown backend",
       [](auto& r) { r.mutable_options()->set_backend(static_cast<v1::JobOptions::Backend>(7)); },
       C::INVALID_ARGUMENT, "options.backend"},
      {"snapshot_every too large", [](auto& r) { r.mutable_options()->set_snapshot_every(200000); },
       C::INVALID_ARGUMENT, "options.snapshot_every"},
      {"label too long", [](auto& r) { r.mutable_options()->set_label(std::string(200, 'x')); },
       C::INVALID_ARGUMENT, "options.label"},
      {"timeout negative", [](auto& r) { r.mutable_options()->set_timeout_s(-1); },
       C::INVALID_ARGUMENT, "options.timeout_s"},
      {"too many nodes", [](auto& r) { r.set_h0(1e-5); }, C::RESOURCE_EXHAUSTED, "h0"},
      {"snapshots of a large mesh",
       [](auto& r) {
         r.set_h0(0.005);
         r.mutable_options()->set_snapshot_every(1);
       },
       C::RESOURCE_EXHAUSTED, "options.snapshot_every"},
      {"GPU on a CPU-only server",
       [](auto& r) { r.mutable_options()->set_backend(v1::JobOptions::BACKEND_GPU); },
       C::FAILED_PRECONDITION, "options.backend"},
  };
  TestServer server;
  auto stub = server.stub();
  for (const BadInput& c : cases) {
    SCOPED_TRACE(c.what);
    v1::MeshRequest request = disk_request(0.1);
    c.spoil(request);
    const StreamResult r = generate(*stub, request);
    EXPECT_EQ(r.status.error_code(), c.code) << r.status.error_message();
    EXPECT_EQ(r.status.error_message().rfind(std::string(c.field) + ":", 0), 0u)
        << r.status.error_message();
    EXPECT_TRUE(r.events.empty());
    v1::JobRef ref;
    auto context = context_with_deadline();
    EXPECT_EQ(stub->Submit(context.get(), request, &ref).error_code(), c.code);
  }
  // The server is still there and nothing is left behind.
  expect_valid_result(generate(*stub, disk_request(0.1)));
  EXPECT_TRUE(no_live_jobs(server));
  const std::string metrics = server.server().metrics().text();
  EXPECT_NE(
      metrics.find("meshd_jobs_total{outcome=\"rejected\"} " + std::to_string(2 * cases.size())),
      std::string::npos)
      << metrics;
}

TEST(MeshService, FullQueueIsUnavailableAtOnce) {
  auto gate = std::make_shared<Gate>();
  ServerOptions options = test_options();
  options.jobs.queue_capacity = 2;
  TestServer server(options, {{"cpu0", Backend::kCpu, gated_cpu_factory(gate, false)}});
  auto stub = server.stub();
  const std::string running = submit(*stub, disk_request(0.2));
  gate->wait_for_waiter();  // the worker holds the first job
  const std::string q1 = submit(*stub, disk_request(0.2));
  const std::string q2 = submit(*stub, disk_request(0.2));
  EXPECT_EQ(get_job(*stub, q2).queue_position(), 1);

  const auto t = std::chrono::steady_clock::now();
  v1::JobRef ref;
  auto context = context_with_deadline();
  const grpc::Status s = stub->Submit(context.get(), disk_request(0.2), &ref);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(s.error_message().find("queue is full"), std::string::npos);
  EXPECT_LT(std::chrono::steady_clock::now() - t, 1s);

  gate->open();
  for (const auto& id : {running, q1, q2})
    EXPECT_EQ(wait_for_state(*stub, id, v1::JOB_STATE_SUCCEEDED).state(), v1::JOB_STATE_SUCCEEDED);
}

TEST(MeshService, HigherPriorityRunsFirst) {
  auto gate = std::make_shared<Gate>();
  TestServer server(test_options(), {{"cpu0", Backend::kCpu, gated_cpu_factory(gate, false)}});
  auto stub = server.stub();
  submit(*stub, disk_request(0.2));
  gate->wait_for_waiter();
  const std::string low = submit(*stub, disk_request(0.2));
  v1::MeshRequest urgent = disk_request(0.2);
  urgent.mutable_options()->set_priority(5);
  const std::string high = submit(*stub, urgent);
  EXPECT_EQ(get_job(*stub, high).queue_position(), 0);
  EXPECT_EQ(get_job(*stub, low).queue_position(), 1);
  gate->open();
  const auto a = wait_for_state(*stub, low, v1::JOB_STATE_SUCCEEDED);
  const auto b = wait_for_state(*stub, high, v1::JOB_STATE_SUCCEEDED);
  EXPECT_LT(b.queue_wait_s(), a.queue_wait_s());
}

TEST(MeshService, CancelWhileQueuedEndsItsStreamAtOnce) {
  auto gate = std::make_shared<Gate>();
  TestServer server(test_options(), {{"cpu0", Backend::kCpu, gated_cpu_factory(gate, false)}});
  auto stub = server.stub();
  const std::string running = submit(*stub, disk_request(0.2));
  gate->wait_for_waiter();
  const std::string queued = submit(*stub, disk_request(0.2));

  StreamResult watched;
  std::thread watcher([&] { watched = watch(*stub, queued); });
  std::this_thread::sleep_for(50ms);
  const auto t = std::chrono::steady_clock::now();
  ASSERT_TRUE(cancel(*stub, queued).ok());
  watcher.join();
  EXPECT_LT(std::chrono::steady_clock::now() - t, 2s);
  EXPECT_EQ(watched.status.error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_EQ(watched.kinds(), std::vector<std::string>{"queued"});
  EXPECT_EQ(get_job(*stub, queued).state(), v1::JOB_STATE_CANCELLED);

  gate->open();
  EXPECT_EQ(wait_for_state(*stub, running, v1::JOB_STATE_SUCCEEDED).state(),
            v1::JOB_STATE_SUCCEEDED);
  EXPECT_TRUE(no_live_jobs(server));
}

TEST(MeshService, CancelWhileRunningStopsWithinAnIteration) {
  TestServer server;
  auto stub = server.stub();
  const std::string id = submit(*stub, endless_request());
  ASSERT_EQ(wait_for_state(*stub, id, v1::JOB_STATE_RUNNING).state(), v1::JOB_STATE_RUNNING);
  // Into its iterations: a fixed wait was too short under sanitizers on a loaded machine.
  const auto running_since = std::chrono::steady_clock::now();
  while (get_job(*stub, id).iteration() == 0 &&
         std::chrono::steady_clock::now() - running_since < 10s)
    std::this_thread::sleep_for(10ms);
  const auto t = std::chrono::steady_clock::now();
  ASSERT_TRUE(cancel(*stub, id).ok());
  const v1::JobInfo info = wait_for_state(*stub, id, v1::JOB_STATE_CANCELLED, 2s);
  EXPECT_EQ(info.state(), v1::JOB_STATE_CANCELLED);
  EXPECT_LT(std::chrono::steady_clock::now() - t, 1s);
  EXPECT_EQ(info.error_code(), static_cast<int>(grpc::StatusCode::CANCELLED));
  EXPECT_GT(info.iteration(), 0);
  // The worker is free again.
  expect_valid_result(generate(*stub, disk_request(0.1)));
}

TEST(MeshService, ClientDeadlineCancelsTheJob) {
  TestServer server;
  auto stub = server.stub();
  const StreamResult r = generate(*stub, endless_request(), 300ms);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  ASSERT_FALSE(r.job_id.empty());
  const v1::JobInfo info = wait_for_state(*stub, r.job_id, v1::JOB_STATE_CANCELLED, 2s);
  EXPECT_EQ(info.state(), v1::JOB_STATE_CANCELLED);
  EXPECT_TRUE(no_live_jobs(server));
  expect_valid_result(generate(*stub, disk_request(0.1)));
}

TEST(MeshService, SubmitTimeoutStopsTheJob) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest request = endless_request();
  request.mutable_options()->set_timeout_s(0.3);
  const std::string id = submit(*stub, request);
  const v1::JobInfo info = wait_for_state(*stub, id, v1::JOB_STATE_CANCELLED, 3s);
  EXPECT_EQ(info.state(), v1::JOB_STATE_CANCELLED);
  EXPECT_EQ(info.error_code(), static_cast<int>(grpc::StatusCode::DEADLINE_EXCEEDED));
}

TEST(MeshService, ClientDisconnectCancelsGenerateButNotSubmit) {
  TestServer server;
  auto stub = server.stub();
  auto context = context_with_deadline(60s);
  auto reader = stub->Generate(context.get(), endless_request());
  v1::MeshEvent event;
  std::string id;
  while (reader->Read(&event)) {
    id = event.job_id();
    if (event.has_progress()) break;
  }
  ASSERT_FALSE(id.empty());
  context->TryCancel();
  reader->Finish();
  EXPECT_EQ(wait_for_state(*stub, id, v1::JOB_STATE_CANCELLED, 2s).state(),
            v1::JOB_STATE_CANCELLED);

  // A submitted job outlives a watcher that goes away.
  const std::string kept = submit(*stub, disk_request(0.05));
  {
    v1::JobRef ref;
    ref.set_job_id(kept);
    auto watch_context = context_with_deadline(60s);
    auto watcher = stub->Watch(watch_context.get(), ref);
    ASSERT_TRUE(watcher->Read(&event));
    watch_context->TryCancel();
    watcher->Finish();
  }
  EXPECT_EQ(wait_for_state(*stub, kept, v1::JOB_STATE_SUCCEEDED).state(), v1::JOB_STATE_SUCCEEDED);
}

// A reader that sleeps while the job streams a snapshot every iteration gets the newest events
// when it reads again, not a backlog of all of them: the transport buffers a few, the server
// keeps one.
TEST(MeshService, SlowReaderGetsCoalescedEvents) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest request = endless_request();
  request.mutable_options()->set_snapshot_every(1);
  auto context = context_with_deadline(60s);
  auto reader = stub->Generate(context.get(), request);
  v1::MeshEvent event;
  ASSERT_TRUE(reader->Read(&event));
  const std::string id = event.job_id();
  std::this_thread::sleep_for(2s);
  const int now = get_job(*stub, id).iteration();
  ASSERT_GT(now, 500);
  int snapshots = 0;
  int latest = 0;
  while (latest < now && reader->Read(&event)) {
    if (event.has_snapshot()) {
      ++snapshots;
      latest = event.snapshot().iteration();
    }
  }
  EXPECT_GE(latest, now);
  EXPECT_LT(snapshots, now / 4) << "the server sent a backlog";
  context->TryCancel();
  reader->Finish();
  EXPECT_TRUE(no_live_jobs(server));
}

TEST(MeshService, EngineFailureFailsOnlyThatJob) {
  for (const ErrorCode code : {ErrorCode::kResourceExhausted, ErrorCode::kInternal}) {
    SCOPED_TRACE(error_code_name(code));
    auto builds = std::make_shared<std::atomic<int>>(0);
    TestServer server(test_options(),
                      {{"gpu-like", Backend::kCpu, failing_cpu_factory(code, 5, builds)}});
    auto stub = server.stub();
    const StreamResult failed = generate(*stub, disk_request(0.1));
    EXPECT_EQ(failed.status.error_code(), code == ErrorCode::kInternal
                                              ? grpc::StatusCode::INTERNAL
                                              : grpc::StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(failed.status.error_message().find("simulated"), std::string::npos);
    // The next job runs, on a rebuilt engine after a fault, on the same one after OOM.
    expect_valid_result(generate(*stub, disk_request(0.1)));
    EXPECT_EQ(builds->load(), code == ErrorCode::kInternal ? 2 : 1);
    EXPECT_NE(server.server().metrics().text().find("meshd_jobs_total{outcome=\"failed\"} 1"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace meshd::testing
