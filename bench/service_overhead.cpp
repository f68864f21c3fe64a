// service_overhead: what the service adds to a job. The same request is meshed in process (the
// conversion, compilation and engine alone, as meshbench runs them) and through meshd over
// loopback gRPC (an in-process server with one warm worker of the same kind, a client on
// meshctl's channel settings that reads every event and assembles the result as meshctl does:
// checked against its size and SHA-256, parsed and converted to the mesh arrays). The runs
// alternate in pairs; the table gives the median of each, and the overhead as the median of the
// pairs' differences (which cancels the drift of a shared machine better than a difference of
// medians).
//
//   service_overhead [--backend cpu|gpu] [--threads T] [--repeat R] [--nodes N]... [REQUEST]
//
// REQUEST defaults to examples/g2_square_hole.textproto; --nodes (default 1000 and 100000)
// rescales its h0 to aim at N nodes.
#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "client/connection.h"
#include "client/request_file.h"
#include "client/result_assembly.h"
#include "core/common/error.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.grpc.pb.h"
#include "server/mesh_server.h"
#include "server/request_conversion.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string backend = "cpu";
  unsigned threads = 0;
  int repeat = 5;
  std::vector<double> nodes;
  std::string request = "examples/g2_square_hole.textproto";
};

[[noreturn]] void usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: service_overhead [--backend cpu|gpu] [--threads T] [--repeat R]\n"
               "                        [--nodes N]... [REQUEST.textproto]\n");
  std::exit(code);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(2);
      return argv[++i];
    };
    if (a == "-h" || a == "--help")
      usage(0);
    else if (a == "--backend")
      o.backend = value();
    else if (a == "--threads")
      o.threads = static_cast<unsigned>(std::stoul(value()));
    else if (a == "--repeat")
      o.repeat = std::max(1, std::stoi(value()));
    else if (a == "--nodes")
      o.nodes.push_back(std::stod(value()));
    else if (!a.empty() && a[0] == '-')
      usage(2);
    else
      o.request = a;
  }
  if (o.nodes.empty()) o.nodes = {1000, 100000};
  if (o.backend != "cpu" && o.backend != "gpu") usage(2);
  return o;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The engine alone: what an in-process caller of core/ pays, the request's node estimate
// sampled over the engine's host threads as meshd's admission samples it over the host's.
// `engine_s` is the engine's own part (its t_mesh).
double in_process(meshd::Engine& engine, const meshd::v1::MeshRequest& request, int64_t& nodes,
                  double& engine_s) {
  const auto t = Clock::now();
  const meshd::JobSpec spec = meshd::to_job_spec(request, {}, engine.host_pool());
  const meshd::MeshResult r = meshd::generate_mesh(spec.plane, engine, nullptr, nullptr);
  const double s = seconds_since(t);
  nodes = static_cast<int64_t>(r.mesh.points.size());
  engine_s = r.stats.t_total;
  return s;
}

// When the events of one call through the service arrived, in seconds from the call.
struct ServiceTiming {
  double queued = 0;   // admission: the request checked and the job queued
  double started = 0;  // a worker took the job
  double done = 0;     // the last event
  double mesh = 0;     // the engine's own time in meshd (the done event's t_mesh)
  double chunk = 0;    // the result's first chunk
  double total = 0;    // the result parsed and checked
};

// Through the service: Generate, every event read, the result assembled, checked and converted
// as meshctl does, so that both paths end with the same mesh arrays in memory.
ServiceTiming through_service(meshd::v1::MeshService::Stub& stub,
                              const meshd::v1::MeshRequest& request, int64_t& nodes) {
  ServiceTiming timing;
  const auto t = Clock::now();
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::minutes(10));
  auto reader = stub.Generate(&context, request);
  meshd::v1::MeshEvent event;
  meshd::cli::ResultAssembly assembly;
  std::optional<meshd::Mesh> mesh;
  while (reader->Read(&event)) {
    if (event.has_queued()) timing.queued = seconds_since(t);
    if (event.has_started()) timing.started = seconds_since(t);
    if (event.has_result_chunk()) {
      if (event.result_chunk().index() == 0) timing.chunk = seconds_since(t);
      assembly.add(event.result_chunk());
    }
    if (event.has_done()) {
      timing.done = seconds_since(t);
      timing.mesh = event.done().stats().t_mesh();
      mesh = std::get<meshd::Mesh>(assembly.finish(event.done()));
    }
  }
  const grpc::Status status = reader->Finish();
  if (!status.ok() || !mesh) {
    std::fprintf(stderr, "service_overhead: the service failed: %s\n",
                 status.error_message().c_str());
    std::exit(1);
  }
  timing.total = seconds_since(t);
  nodes = static_cast<int64_t>(mesh->points.size());
  return timing;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  spdlog::set_level(spdlog::level::warn);
  try {
    const meshd::Backend kind = opt.backend == "gpu" ? meshd::Backend::kGpu : meshd::Backend::kCpu;
    const meshd::WorkerEngineFactory factory = kind == meshd::Backend::kGpu
                                                   ? meshd::gpu_engine_factory(0, opt.threads)
                                                   : meshd::cpu_engine_factory(opt.threads);
    const auto engine = factory();
    meshd::ServerOptions options;
    options.listen = "127.0.0.1:0";
    meshd::MeshServer server(options, {{"bench", kind, factory}});
    server.start();
    // The channel meshctl opens.
    auto stub = meshd::v1::MeshService::NewStub(grpc::CreateCustomChannel(
        "127.0.0.1:" + std::to_string(server.port()), grpc::InsecureChannelCredentials(),
        meshd::cli::channel_arguments()));

    const meshd::v1::MeshRequest base = meshd::read_request_file(opt.request);
    std::printf("request %s on %s, median of %d alternating runs each (%d below 10k nodes)\n\n",
                opt.request.c_str(), engine->device().c_str(), opt.repeat, 5 * opt.repeat);
    // Where the service's time goes: the events' arrival times (medians), from the call.
    std::printf(
        "| nodes | in process ms | engine in process ms | through meshd ms | overhead ms "
        "| overhead %% | queued at ms | started at ms | engine in meshd ms | first chunk at ms "
        "| done at ms |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const double target : opt.nodes) {
      meshd::v1::MeshRequest request = base;
      request.set_h0(meshd::h0_for_node_count(meshd::to_problem(base), target));
      request.mutable_options()->set_backend(kind == meshd::Backend::kGpu
                                                 ? meshd::v1::JobOptions::BACKEND_GPU
                                                 : meshd::v1::JobOptions::BACKEND_CPU);
      int64_t nodes_a = 0, nodes_b = 0;
      double engine_s = 0;
      in_process(engine->engine(), request, nodes_a, engine_s);  // warm both paths at this size
      through_service(*stub, request, nodes_b);
      std::vector<double> a, engine_a, b, difference, queued, started, done, mesh, chunk;
      // Small jobs take milliseconds and vary more: more runs.
      const int repeat = nodes_a < 10'000 ? 5 * opt.repeat : opt.repeat;
      for (int r = 0; r < repeat; ++r) {
        a.push_back(in_process(engine->engine(), request, nodes_a, engine_s));
        engine_a.push_back(engine_s);
        const ServiceTiming timing = through_service(*stub, request, nodes_b);
        b.push_back(timing.total);
        difference.push_back(b.back() - a.back());
        queued.push_back(timing.queued);
        started.push_back(timing.started);
        done.push_back(timing.done);
        mesh.push_back(timing.mesh);
        chunk.push_back(timing.chunk);
      }
      if (nodes_a != nodes_b) {
        std::fprintf(stderr, "service_overhead: node counts differ (%lld vs %lld)\n",
                     static_cast<long long>(nodes_a), static_cast<long long>(nodes_b));
        return 1;
      }
      const double ma = median(a), mb = median(b), md = median(difference);
      std::printf(
          "| %lld | %.2f | %.2f | %.2f | %.2f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
          static_cast<long long>(nodes_a), 1e3 * ma, 1e3 * median(engine_a), 1e3 * mb, 1e3 * md,
          100 * md / ma, 1e3 * median(queued), 1e3 * median(started), 1e3 * median(mesh),
          1e3 * median(chunk), 1e3 * median(done));
      std::fflush(stdout);
    }
    server.shutdown(std::chrono::milliseconds(0));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "service_overhead: %s\n", e.what());
    return 2;
  }
  return 0;
}
