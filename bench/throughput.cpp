// throughput: many small jobs through meshd at once, as a simulation pipeline sends them. One
// process runs many concurrent gRPC clients (callback API, one Generate call per job, every
// event read) against a meshd at --address, or against one it starts in process with the meshd
// flags given after "--". Closed loop (--clients calls in flight, each finished call starting
// the next) or open loop (--rate jobs/s, Poisson arrivals, however many are in flight). Prints
// jobs/s, latency percentiles, the mesh time the server reports and which backend ran the jobs,
// as a table for RESULTS.md. Exits 1 when any job failed or went unaccounted.
//
//   throughput [--address HOST:PORT] [--jobs N] [--clients C | --rate R] [--nodes N[,N...]]
//              [--job-backend auto|gpu|cpu] [--channels K] [--seed S] [--deadline SECONDS]
//              [--events] [--latencies FILE] [REQUEST.textproto] [-- meshd flags...]
//
// --nodes rescales the request's h0 to aim at each size; every job picks one at random.
// --events adds a line after the table: the events a job's stream carried, on average (queued
// ones apart: a stream says queued again when its position changes, at most every 100 ms).
// --latencies writes each job as a CSV line in the order they ended (when it started after the
// run began, its latency and the server's mesh time), so that a tail can be traced to its jobs.
#include <grpcpp/grpcpp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "client/request_file.h"
#include "core/distmesh/node_estimate.h"
#include "meshd/v1/service.grpc.pb.h"
#include "server/mesh_server.h"
#include "server/request_conversion.h"
#include "server/server_options.h"

namespace {

using Clock = std::chrono::steady_clock;
using meshd::v1::MeshEvent;
using meshd::v1::MeshRequest;

struct Options {
  std::string address;  // empty: an in-process meshd
  std::vector<std::string> server_args;
  int jobs = 1000;
  int clients = 32;
  int channels = 4;  // connections, so that one connection's thread is not the limit
  double rate = 0;   // jobs/s; 0: closed loop
  std::vector<double> nodes{2000};
  std::string job_backend = "auto";  // what each request asks for
  unsigned seed = 1;
  double deadline_s = 120;
  bool events = false;    // also print the events each job's stream carried
  std::string latencies;  // a CSV of every job; empty: none
  std::string request;    // empty: a unit disk
};

[[noreturn]] void usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: throughput [--address HOST:PORT] [--jobs N] [--clients C | --rate R]\n"
               "                  [--nodes N[,N...]] [--job-backend auto|gpu|cpu]\n"
               "                  [--channels K] [--seed S] [--deadline SECONDS] [--events]\n"
               "                  [--latencies FILE] [REQUEST.textproto] [-- meshd flags...]\n");
  std::exit(code);
}

std::vector<double> numbers(const std::string& list) {
  std::vector<double> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(2);
      return argv[++i];
    };
    if (a == "-h" || a == "--help") usage(0);
    if (a == "--") {
      o.server_args.assign(argv + i + 1, argv + argc);
      break;
    }
    if (a == "--address")
      o.address = value();
    else if (a == "--jobs")
      o.jobs = std::stoi(value());
    else if (a == "--clients")
      o.clients = std::stoi(value());
    else if (a == "--rate")
      o.rate = std::stod(value());
    else if (a == "--channels")
      o.channels = std::stoi(value());
    else if (a == "--job-backend")
      o.job_backend = value();
    else if (a == "--nodes")
      o.nodes = numbers(value());
    else if (a == "--seed")
      o.seed = static_cast<unsigned>(std::stoul(value()));
    else if (a == "--deadline")
      o.deadline_s = std::stod(value());
    else if (a == "--events")
      o.events = true;
    else if (a == "--latencies")
      o.latencies = value();
    else if (!a.empty() && a[0] == '-')
      usage(2);
    else
      o.request = a;
  }
  if (o.jobs < 1 || o.clients < 1 || o.channels < 1 || o.rate < 0 || o.nodes.empty()) usage(2);
  if (o.job_backend != "auto" && o.job_backend != "gpu" && o.job_backend != "cpu") usage(2);
  return o;
}

// What one job's call ended with.
struct Outcome {
  grpc::StatusCode code = grpc::StatusCode::UNKNOWN;
  bool done = false;  // the done event arrived
  int events = 0;     // events read, of every kind
  int queued = 0;     // queued events read (the first and each position change)
  Clock::time_point start;
  double latency_s = 0;
  double mesh_s = 0;  // the server's own time for the mesh
  meshd::v1::JobOptions::Backend backend = meshd::v1::JobOptions::BACKEND_AUTO;
};

// The jobs of one run: which to start next, and what the finished ones ended with.
class Load {
 public:
  Load(const Options& options, std::vector<std::unique_ptr<meshd::v1::MeshService::Stub>>& stubs,
       const std::vector<MeshRequest>& requests)
      : options_(options), stubs_(stubs), requests_(requests), rng_(options.seed) {}

  // Starts the next job; false when all have started.
  bool start_next();
  void finished(const Outcome& outcome);
  // Blocks until every started job has finished.
  void wait();
  const std::vector<Outcome>& outcomes() const { return outcomes_; }

 private:
  const Options& options_;
  std::vector<std::unique_ptr<meshd::v1::MeshService::Stub>>& stubs_;
  const std::vector<MeshRequest>& requests_;
  std::mutex mutex_;
  std::condition_variable all_done_;
  std::mt19937 rng_;
  int started_ = 0;
  std::vector<Outcome> outcomes_;
};

class Call final : public grpc::ClientReadReactor<MeshEvent> {
 public:
  Call(Load& load, meshd::v1::MeshService::Stub& stub, const MeshRequest& request,
       double deadline_s)
      : load_(load), start_(Clock::now()) {
    context_.set_deadline(std::chrono::system_clock::now() +
                          std::chrono::milliseconds(static_cast<int64_t>(deadline_s * 1e3)));
    stub.async()->Generate(&context_, &request, this);
    StartRead(&event_);
    StartCall();
  }

  void OnReadDone(bool ok) override {
    if (!ok) return;  // the stream ended: OnDone follows
    ++outcome_.events;
    if (event_.has_queued()) ++outcome_.queued;
    if (event_.has_done()) {
      outcome_.done = true;
      outcome_.mesh_s = event_.done().stats().t_mesh();
      outcome_.backend = event_.done().backend();
    }
    StartRead(&event_);
  }

  void OnDone(const grpc::Status& status) override {
    outcome_.code = status.error_code();
    outcome_.start = start_;
    outcome_.latency_s = std::chrono::duration<double>(Clock::now() - start_).count();
    Load& load = load_;
    const Outcome outcome = outcome_;
    delete this;
    load.finished(outcome);
  }

 private:
  Load& load_;
  const Clock::time_point start_;
  grpc::ClientContext context_;
  MeshEvent event_;
  Outcome outcome_;
};

bool Load::start_next() {
  size_t pick = 0, channel = 0;
  {
    std::lock_guard lock(mutex_);
    if (started_ >= options_.jobs) return false;
    channel = static_cast<size_t>(started_++) % stubs_.size();
    pick = std::uniform_int_distribution<size_t>(0, requests_.size() - 1)(rng_);
  }
  new Call(*this, *stubs_[channel], requests_[pick], options_.deadline_s);
  return true;
}

void Load::finished(const Outcome& outcome) {
  {
    std::lock_guard lock(mutex_);
    outcomes_.push_back(outcome);
    if (static_cast<int>(outcomes_.size()) == options_.jobs) all_done_.notify_all();
  }
  if (options_.rate == 0) start_next();  // closed loop: a finished call starts the next
}

void Load::wait() {
  std::unique_lock lock(mutex_);
  all_done_.wait(lock, [&] { return static_cast<int>(outcomes_.size()) == options_.jobs; });
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

std::vector<MeshRequest> requests_for(const Options& o) {
  MeshRequest base;
  if (o.request.empty()) {
    base.mutable_geometry()->mutable_circle()->set_radius(1.0);
    base.set_h0(0.1);
  } else {
    base = meshd::read_request_file(o.request);
  }
  base.mutable_options()->set_snapshot_every(0);
  base.mutable_options()->set_backend(o.job_backend == "gpu" ? meshd::v1::JobOptions::BACKEND_GPU
                                      : o.job_backend == "cpu"
                                          ? meshd::v1::JobOptions::BACKEND_CPU
                                          : meshd::v1::JobOptions::BACKEND_AUTO);
  std::vector<MeshRequest> out;
  for (const double n : o.nodes) {
    MeshRequest r = base;
    r.set_h0(meshd::h0_for_node_count(meshd::to_problem(base), n));
    out.push_back(std::move(r));
  }
  return out;
}

// Every job, one CSV line each: start (s after the run began), latency and mesh time (ms), code.
void write_latencies(const std::string& path, const std::vector<Outcome>& outcomes,
                     Clock::time_point run_start) {
  FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw std::runtime_error("cannot write " + path);
  std::fprintf(out, "start_s,latency_ms,mesh_ms,code\n");
  for (const Outcome& r : outcomes)
    std::fprintf(out, "%.6f,%.3f,%.3f,%d\n",
                 std::chrono::duration<double>(r.start - run_start).count(), r.latency_s * 1e3,
                 r.mesh_s * 1e3, static_cast<int>(r.code));
  std::fclose(out);
}

// The table: one row for this run.
int report(const Options& o, const std::vector<Outcome>& outcomes, double seconds) {
  std::vector<double> latency, mesh;
  std::map<std::string, int> failures;
  int ok = 0, gpu = 0, cpu = 0;
  for (const Outcome& r : outcomes) {
    if (r.code == grpc::StatusCode::OK && r.done) {
      ++ok;
      latency.push_back(r.latency_s * 1e3);
      mesh.push_back(r.mesh_s * 1e3);
      (r.backend == meshd::v1::JobOptions::BACKEND_GPU ? gpu : cpu)++;
    } else {
      ++failures[r.done ? "done, then status " + std::to_string(r.code)
                        : "status " + std::to_string(r.code)];
    }
  }
  std::string sizes;
  for (const double n : o.nodes) sizes += (sizes.empty() ? "" : ",") + std::to_string(int(n));
  const std::string load = o.rate > 0 ? "open loop at " + std::to_string(int(o.rate)) + " jobs/s"
                                      : "closed loop of " + std::to_string(o.clients) + " clients";
  std::printf(
      "| jobs | nodes | load | ok | jobs/s | p50 ms | p90 ms | p99 ms | max ms "
      "| mesh ms (mean) | mesh ms (p99) | on GPU | on CPU |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  double mesh_mean = 0;
  for (const double m : mesh) mesh_mean += m / static_cast<double>(mesh.size());
  std::printf("| %d | %s | %s | %d | %.0f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %d | %d |\n",
              o.jobs, sizes.c_str(), load.c_str(), ok, ok / seconds, percentile(latency, 0.5),
              percentile(latency, 0.9), percentile(latency, 0.99), percentile(latency, 1.0),
              mesh_mean, percentile(mesh, 0.99), gpu, cpu);
  if (o.events) {
    double events = 0, queued = 0;
    for (const Outcome& r : outcomes) {
      events += r.events;
      queued += r.queued;
    }
    const double n = std::max<double>(1, static_cast<double>(outcomes.size()));
    std::printf("events per job: %.1f, of them queued %.1f\n", events / n, queued / n);
  }
  for (const auto& [what, count] : failures)
    std::printf("failed: %d jobs with %s\n", count, what.c_str());
  const bool accounted = static_cast<int>(outcomes.size()) == o.jobs;
  if (!accounted) std::printf("unaccounted: %zu of %d jobs ended\n", outcomes.size(), o.jobs);
  return ok == o.jobs && accounted ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::unique_ptr<meshd::MeshServer> server;
  std::string address = o.address;
  try {
    if (address.empty()) {
      bool help = false;
      std::vector<std::string> args = o.server_args;
      args.insert(args.end(), {"--listen", "127.0.0.1:0", "--log-level", "warn"});
      meshd::ServerOptions server_options = meshd::parse_server_options(args, help);
      spdlog::set_level(spdlog::level::warn);
      // Room for every job: an open loop past the server's rate measures its latency, not the
      // queue's refusals.
      server_options.jobs.queue_capacity =
          std::max<size_t>(server_options.jobs.queue_capacity, static_cast<size_t>(o.jobs));
      server = std::make_unique<meshd::MeshServer>(server_options);
      server->start();
      address = "127.0.0.1:" + std::to_string(server->port());
    }
    const std::vector<MeshRequest> requests = requests_for(o);
    std::vector<std::unique_ptr<meshd::v1::MeshService::Stub>> stubs;
    for (int c = 0; c < o.channels; ++c) {
      grpc::ChannelArguments channel_args;
      channel_args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);  // a connection of its own
      auto channel =
          grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), channel_args);
      // Connected before the clock starts: a pipeline keeps its connection, so a job's latency
      // is measured without the handshake of a channel's first call.
      if (!channel->WaitForConnected(std::chrono::system_clock::now() + std::chrono::seconds(10)))
        throw std::runtime_error("cannot connect to " + address);
      stubs.push_back(meshd::v1::MeshService::NewStub(channel));
    }
    Load load(o, stubs, requests);
    const auto t = Clock::now();
    if (o.rate > 0) {
      std::mt19937 rng(o.seed + 1);
      std::exponential_distribution<double> gap(o.rate);
      auto next = Clock::now();
      while (load.start_next()) {
        next +=
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(gap(rng)));
        std::this_thread::sleep_until(next);
      }
    } else {
      for (int c = 0; c < o.clients && load.start_next(); ++c) {
      }
    }
    load.wait();
    const double seconds = std::chrono::duration<double>(Clock::now() - t).count();
    const int code = report(o, load.outcomes(), seconds);
    if (!o.latencies.empty()) write_latencies(o.latencies, load.outcomes(), t);
    if (server) server->shutdown(std::chrono::milliseconds(0));
    return code;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "throughput: %s\n", e.what());
    return 2;
  }
}
