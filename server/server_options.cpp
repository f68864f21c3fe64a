#include "server/server_options.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <thread>

#include "core/common/error.h"

namespace meshd {

const char* server_usage() {
  return R"(usage: meshd [flags]

  --listen HOST:PORT        gRPC address (default 127.0.0.1:50051; port 0 picks a free port
                            and logs it)
  --metrics HOST:PORT       serve Prometheus metrics at http://HOST:PORT/metrics (default: off)
  --backend auto|gpu|cpu    auto: GPU workers on every visible device and the CPU workers
                            beside them (BACKEND_AUTO jobs go where they finish first);
                            gpu: refuse to start without a GPU; cpu: no GPU workers
  --gpu-workers N           GPU workers per device, [1, 64] (default 4): each has its own
                            engine and stream, so that small jobs share the device
  --cpu-workers N           CPU workers, [1, 256] (default 1)
  --cpu-threads N           threads of each CPU worker, [0, 1024] (default 0: the cores
                            shared among the CPU workers)
  --queue-capacity N        jobs that may wait, [1, 100000] (default 64); more: UNAVAILABLE
  --retention SECONDS       how long finished jobs and their results are kept (default 600)
  --max-retained N          finished jobs kept at most (default 1000)
  --drain-timeout SECONDS   on SIGTERM, how long running jobs may finish (default 30)
  --max-nodes N             largest estimated mesh accepted (default 5000000)
  --max-request-mb N        largest request message accepted, in MiB, [1, 2047] (default
                            256: a polygon of 5 million vertices takes about 100)
  --max-snapshot-nodes N    largest mesh whose snapshots may stream, [0, 100000] (default
                            50000; a snapshot must fit a client's 4 MiB message limit); a
                            volume's limit is 2/5 of it
  --max-grid-samples N      samples of the distance grids of one shape tree, [4, 1e9]
                            (default 16777216: a 4096 x 4096 image)
  --max-size-grid-values N  samples of a request's size-field grids together, [4, 1e9]
                            (default 16777216: 4096 x 4096, 4 bytes each)
  --tls-cert FILE --tls-key FILE
                            serve TLS with this PEM certificate chain and key
  --tls-client-ca FILE      also require client certificates signed by this PEM CA
  --token-file FILE         require "authorization: Bearer <token>" with the token in FILE
  --log-level LEVEL         trace, debug, info, warn, error (default info)
  --config FILE             read "flag = value" lines (names without --) before the flags
  --help                    this text
)";
}

namespace {

double number(const std::string& flag, const std::string& value, double lo, double hi) {
  double v = NAN;
  try {
    size_t used = 0;
    v = std::stod(value, &used);
    if (used != value.size()) v = NAN;
  } catch (const std::exception&) {
  }
  if (!(v >= lo && v <= hi)) {
    throw_invalid("--" + flag, "must be a number in [" + std::to_string(lo) + ", " +
                                   std::to_string(hi) + "] (got '" + value + "')");
  }
  return v;
}

int64_t integer(const std::string& flag, const std::string& value, double lo, double hi) {
  const double v = number(flag, value, lo, hi);
  if (v != std::floor(v)) throw_invalid("--" + flag, "must be a whole number (got " + value + ")");
  return static_cast<int64_t>(v);
}

using Setter = std::function<void(ServerOptions&, const std::string& flag, const std::string&)>;

const std::map<std::string, Setter>& setters() {
  using O = ServerOptions;
  using S = const std::string&;
  static const std::map<std::string, Setter> kSetters = {
      {"listen", [](O& o, S, S v) { o.listen = v; }},
      {"metrics", [](O& o, S, S v) { o.metrics = v; }},
      {"backend",
       [](O& o, S f, S v) {
         if (v == "auto")
           o.backend = Backend::kAuto;
         else if (v == "gpu")
           o.backend = Backend::kGpu;
         else if (v == "cpu")
           o.backend = Backend::kCpu;
         else
           throw_invalid("--" + f, "must be auto, gpu or cpu (got '" + v + "')");
       }},
      {"max-request-mb",
       [](O& o, S f, S v) { o.max_request_mb = static_cast<int>(integer(f, v, 1, 2047)); }},
      {"gpu-workers",
       [](O& o, S f, S v) { o.gpu_workers = static_cast<int>(integer(f, v, 1, 64)); }},
      {"cpu-workers",
       [](O& o, S f, S v) { o.cpu_workers = static_cast<int>(integer(f, v, 1, 256)); }},
      {"cpu-threads",
       [](O& o, S f, S v) { o.cpu_threads = static_cast<unsigned>(integer(f, v, 0, 1024)); }},
      {"queue-capacity",
       [](O& o, S f, S v) { o.jobs.queue_capacity = static_cast<size_t>(integer(f, v, 1, 1e5)); }},
      {"retention",
       [](O& o, S f, S v) {
         o.jobs.retention =
             std::chrono::milliseconds(static_cast<int64_t>(1000 * number(f, v, 0, 7 * 86400)));
       }},
      {"max-retained",
       [](O& o, S f, S v) { o.jobs.max_retained = static_cast<size_t>(integer(f, v, 0, 1e6)); }},
      {"drain-timeout", [](O& o, S f, S v) { o.drain_timeout_s = number(f, v, 0, 86400); }},
      {"max-nodes", [](O& o, S f, S v) { o.jobs.limits.max_nodes = integer(f, v, 3, 1e9); }},
      {"max-snapshot-nodes",
       [](O& o, S f, S v) {
         o.jobs.limits.max_snapshot_nodes = static_cast<int>(integer(f, v, 0, 1e5));
       }},
      {"max-grid-samples",
       [](O& o, S f, S v) { o.jobs.limits.max_grid_samples = integer(f, v, 4, 1e9); }},
      {"max-size-grid-values",
       [](O& o, S f, S v) { o.jobs.limits.max_size_grid_values = integer(f, v, 4, 1e9); }},
      {"tls-cert", [](O& o, S, S v) { o.tls_cert = v; }},
      {"tls-key", [](O& o, S, S v) { o.tls_key = v; }},
      {"tls-client-ca", [](O& o, S, S v) { o.tls_client_ca = v; }},
      {"token-file", [](O& o, S, S v) { o.token_file = v; }},
      {"log-level",
       [](O& o, S f, S v) {
         if (spdlog::level::from_str(v) == spdlog::level::off && v != "off")
           throw_invalid("--" + f,
                         "must be trace, debug, info, warn, error or off (got '" + v + "')");
         o.log_level = v;
       }},
  };
  return kSetters;
}

void set(ServerOptions& o, const std::string& flag, const std::string& value) {
  const auto it = setters().find(flag);
  if (it == setters().end()) throw_invalid("--" + flag, "unknown flag; see meshd --help");
  it->second(o, flag, value);
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

void read_config(ServerOptions& o, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw_invalid("--config", "cannot read " + path);
  std::string line;
  for (int number_of_line = 1; std::getline(in, line); ++number_of_line) {
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos) {
      throw_invalid("--config",
                    path + ":" + std::to_string(number_of_line) + ": expected 'name = value'");
    }
    set(o, trimmed(line.substr(0, eq)), trimmed(line.substr(eq + 1)));
  }
}

}  // namespace

ServerOptions parse_server_options(const std::vector<std::string>& args, bool& help) {
  help = false;
  std::vector<std::pair<std::string, std::string>> flags;
  std::string config;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    if (a == "--help" || a == "-h") {
      help = true;
      continue;
    }
    if (a.rfind("--", 0) != 0) throw_invalid(a, "unexpected argument; see meshd --help");
    a = a.substr(2);
    std::string value;
    if (const auto eq = a.find('='); eq != std::string::npos) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
    } else {
      if (i + 1 >= args.size()) throw_invalid("--" + a, "needs a value");
      value = args[++i];
    }
    if (a == "config")
      config = value;
    else
      flags.emplace_back(a, value);
  }
  ServerOptions o;
  if (!config.empty()) read_config(o, config);
  for (const auto& [flag, value] : flags) set(o, flag, value);
  if (o.tls_cert.empty() != o.tls_key.empty())
    throw_invalid("--tls-cert", "--tls-cert and --tls-key go together");
  if (!o.tls_client_ca.empty() && o.tls_cert.empty())
    throw_invalid("--tls-client-ca", "client certificates need TLS: give --tls-cert and --tls-key");
  return o;
}

std::vector<WorkerSpec> workers_for(const ServerOptions& o) {
  std::vector<WorkerSpec> out;
  const int gpus = o.backend == Backend::kCpu ? 0 : usable_gpu_count();
  if (o.backend == Backend::kGpu && gpus == 0) {
    throw Error(ErrorCode::kUnavailable, "--backend",
                "--backend gpu, but no GPU is visible (or this build has no GPU engine)");
  }
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  // The host's share of a GPU job (the worst-element optimisation) on the cores shared among
  // the GPU workers.
  const unsigned gpu_host_threads =
      gpus == 0 ? 1u : std::max(1u, cores / static_cast<unsigned>(gpus * o.gpu_workers));
  for (int d = 0; d < gpus; ++d) {
    for (int k = 0; k < o.gpu_workers; ++k) {
      const std::string name =
          "gpu" + std::to_string(d) + (o.gpu_workers > 1 ? "." + std::to_string(k) : std::string());
      out.push_back({name, Backend::kGpu, gpu_engine_factory(d, gpu_host_threads)});
    }
  }
  const unsigned threads = o.cpu_threads > 0
                               ? o.cpu_threads
                               : std::max(1u, cores / static_cast<unsigned>(o.cpu_workers));
  for (int c = 0; c < o.cpu_workers; ++c)
    out.push_back({"cpu" + std::to_string(c), Backend::kCpu, cpu_engine_factory(threads), threads});
  if (gpus == 0) {
    spdlog::info("no GPU {}: serving on the CPU ({} worker{} of {} threads)",
                 o.backend == Backend::kCpu ? "used (--backend cpu)" : "visible", o.cpu_workers,
                 o.cpu_workers == 1 ? "" : "s", threads);
  }
  return out;
}

}  // namespace meshd
