// meshbench: meshes request files with the engine alone (no service) and prints one table row
// per request: sizes, iterations, time per phase and quality. Rows paste into RESULTS.md.
//
//   meshbench [--backend cpu] [--threads T] [--nodes N] [--repeat R] [-o OUT]... REQUEST...
//
// --nodes rescales h0 so that the estimate aims at N nodes; -o writes each mesh, with {name}
// replaced by the request file's stem (format from the extension: .msh .msh22 .vtu .svg).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "client/request_file.h"
#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/mesh/mesh_file.h"
#include "core/mesh/validity.h"
#include "server/request_conversion.h"
#ifdef MESHD_HAVE_CUDA
#include "kernels/gpu_engine.h"
#endif

namespace {

struct Options {
  std::string backend = "cpu";
  std::string force_sum = "gather";
  bool exact_scale = false;
  bool step_graph = true;
  bool bars_graph = true;
  bool steps_together = true;
  bool one_block = true;
  unsigned threads = 0;
  double nodes = 0;
  int repeat = 1;
  bool phases = false;
  std::vector<std::string> outputs;
  std::vector<std::string> requests;
};

[[noreturn]] void usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: meshbench [--backend cpu|gpu] [--force-sum gather|atomic] [--threads T]\n"
               "                 [--exact-scale] [--no-step-graph] [--no-bars-graph] [--nodes N]\n"
               "                 [--no-steps-together] [--no-one-block] [--repeat R]\n"
               "                 [--phases] [-o OUT]... REQUEST.textproto...\n"
               "  --force-sum how the GPU engine sums bar forces per node: a CSR gather\n"
               "              (default, reproducible) or float atomics (for comparison)\n"
               "  --exact-scale   the GPU engine measures the bars before every step (by default\n"
               "              it takes the L0 scale from the step before)\n"
               "  --no-step-graph the GPU engine launches a step's kernels one by one and waits\n"
               "              for each step (by default up to 32 steps run on the device\n"
               "              without the host: one cooperative launch, else a CUDA graph)\n"
               "  --no-steps-together those steps run through the CUDA graph's loop\n"
               "  --no-bars-graph the GPU engine launches a retriangulation's filter, bars and\n"
               "              CSR one by one (by default, up to 2^18 triangles, one CUDA graph)\n"
               "  --no-one-block the GPU engine runs a small triangulation's repairs and bars\n"
               "              as kernels one by one (by default, up to 8,192 triangles, one\n"
               "              block's launch each)\n"
               "  --nodes N   rescale h0 so that the mesh aims at about N nodes\n"
               "  --repeat R  mesh each request R times and report the fastest run\n"
               "  --phases    after the table, one more with the seconds of each phase\n"
               "  -o OUT      write each mesh to OUT ({name} = request file stem; .msh .msh22\n"
               "              .vtu .svg); may be given several times\n");
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
    else if (a == "--force-sum")
      o.force_sum = value();
    else if (a == "--exact-scale")
      o.exact_scale = true;
    else if (a == "--no-step-graph")
      o.step_graph = false;
    else if (a == "--no-bars-graph")
      o.bars_graph = false;
    else if (a == "--no-steps-together")
      o.steps_together = false;
    else if (a == "--no-one-block")
      o.one_block = false;
    else if (a == "--threads")
      o.threads = static_cast<unsigned>(std::stoul(value()));
    else if (a == "--nodes")
      o.nodes = std::stod(value());
    else if (a == "--repeat")
      o.repeat = std::max(1, std::stoi(value()));
    else if (a == "--phases")
      o.phases = true;
    else if (a == "-o")
      o.outputs.push_back(value());
    else if (!a.empty() && a[0] == '-')
      usage(2);
    else
      o.requests.push_back(a);
  }
  if (o.requests.empty()) usage(2);
  if (o.backend != "cpu" && o.backend != "gpu") usage(2);
  if (o.force_sum != "gather" && o.force_sum != "atomic") usage(2);
#ifndef MESHD_HAVE_CUDA
  if (o.backend == "gpu") {
    std::fprintf(stderr, "meshbench: this build has no GPU engine (built without nvcc)\n");
    std::exit(2);
  }
#endif
  return o;
}

// The engine for --backend; the GPU one warmed up so that start-up stays out of the table.
std::unique_ptr<meshd::Engine> make_engine([[maybe_unused]] const Options& o,
                                           meshd::ThreadPool& pool) {
#ifdef MESHD_HAVE_CUDA
  if (o.backend == "gpu") {
    auto gpu = std::make_unique<meshd::GpuEngine>(0);
    if (o.force_sum == "atomic") gpu->set_force_sum(meshd::GpuEngine::ForceSum::kAtomic);
    gpu->set_lagged_scale(!o.exact_scale);
    if (!o.step_graph) gpu->set_step_graph(false);
    if (!o.bars_graph) gpu->set_replayed_triangles(0);
    if (!o.steps_together) gpu->set_steps_together(false);
    if (!o.one_block) gpu->set_one_block_topology(false);
    gpu->set_host_pool(&pool);
    gpu->warm_up();
    return gpu;
  }
#endif
  return std::make_unique<meshd::CpuEngine>(pool);
}

std::string expand(std::string pattern, const std::string& name) {
  for (size_t at; (at = pattern.find("{name}")) != std::string::npos;) pattern.replace(at, 6, name);
  return pattern;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  meshd::ThreadPool pool(opt.threads);
  std::unique_ptr<meshd::Engine> engine;
  try {
    engine = make_engine(opt, pool);
  } catch (const meshd::Error& e) {
    std::fprintf(stderr, "meshbench: %s\n", e.what());
    return 2;
  }
#ifdef MESHD_HAVE_CUDA
  if (opt.backend == "gpu") {
    std::printf("device: %s; device-to-device copy %.0f GB/s (read + write)\n\n",
                meshd::gpu_device_name(0).c_str(), meshd::measure_copy_bandwidth(0));
  }
#endif
  std::printf(
      "| request | backend | nodes | triangles | levels | iterations | equiv. iter "
      "| retri (repair/full) | fallbacks / refills | flips | t_tri s | t_forces s | us/iter "
      "| GB/s (model) | t_cleanup s | t_total s | q_min | q_mean | min angle | trapped |\n");
  std::printf(
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int failures = 0;
  std::vector<std::string> phase_rows;
  for (const std::string& path : opt.requests) {
    const std::string name = std::filesystem::path(path).stem().string();
    try {
      meshd::Problem problem = meshd::to_problem(meshd::read_request_file(path));
      if (opt.nodes > 0) problem.h0 = meshd::h0_for_node_count(problem, opt.nodes);
      const meshd::CompiledProblem compiled = meshd::compile_problem(problem);
      meshd::MeshResult best;
      for (int r = 0; r < opt.repeat; ++r) {
        meshd::MeshResult result = meshd::generate_mesh(compiled, *engine, nullptr, nullptr);
        if (r == 0 || result.stats.t_total < best.stats.t_total) best = std::move(result);
      }
      const auto& s = best.stats;
      const auto validity = meshd::check_validity(best.mesh);
      const int steps = s.iterations + s.cleanup_iterations;
      const double us_per_step = steps > 0 ? 1e6 * s.t_forces / steps : 0.0;
      // Bars of a valid mesh: each interior edge is shared by two triangles.
      const int64_t bars = static_cast<int64_t>(
          (3 * best.mesh.triangles.size() + best.mesh.boundary_edges.size()) / 2);
      const double gbps =
          us_per_step > 0.0 ? meshd::iteration_bytes(static_cast<int64_t>(best.mesh.points.size()),
                                                     bars, !compiled.size.uniform()) /
                                  (us_per_step * 1e3)
                            : 0.0;
      std::printf(
          "| %s | %s | %zu | %zu | %d | %d | %.0f | %d (%d/%d) | %d / %d | %lld | %.3f | %.3f "
          "| %.1f | %.0f | %.3f | %.3f | %.3f | %.4f | %.1f | %lld |%s\n",
          name.c_str(), engine->name(), best.mesh.points.size(), best.mesh.triangles.size(),
          s.levels, steps, s.equivalent_iterations, s.retriangulations,
          s.retriangulations - s.full_triangulations, s.full_triangulations, s.repair_fallbacks,
          s.fold_refills, static_cast<long long>(s.flips), s.t_triangulation, s.t_forces,
          us_per_step, gbps, s.t_cleanup, s.t_total, best.quality.q_min, best.quality.q_mean,
          best.quality.min_angle_deg, static_cast<long long>(s.trapped_removed),
          validity.problems.empty() ? "" : (" INVALID: " + validity.problems[0]).c_str());
      if (!validity.problems.empty() || !s.converged) ++failures;
      char row[512];
      std::snprintf(row, sizeof row,
                    "| %s | %s | %zu | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f |\n",
                    name.c_str(), engine->name(), best.mesh.points.size(), s.t_initial,
                    s.t_triangulation - s.t_full_triangulation, s.t_full_triangulation, s.t_forces,
                    s.t_density, s.t_cleanup, s.t_finish, s.t_total);
      phase_rows.push_back(row);
      for (const std::string& out : opt.outputs) {
        const std::string file = expand(out, name);
        meshd::write_mesh_file(best.mesh, file, meshd::format_from_path(file));
      }
    } catch (const meshd::Error& e) {
      std::fprintf(stderr, "meshbench: %s: %s: %s\n", path.c_str(),
                   meshd::error_code_name(e.code()), e.what());
      ++failures;
    }
  }
  if (opt.phases) {
    // t_cleanup overlaps the others: its triangulations and steps count there too.
    std::printf(
        "\n| request | backend | nodes | t_initial | t_repair | t_full | t_forces | t_density "
        "| t_cleanup | t_finish | t_total |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& row : phase_rows) std::printf("%s", row.c_str());
  }
  return failures == 0 ? 0 : 1;
}
