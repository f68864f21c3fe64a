// meshbench3d: meshes the 3D benchmark domains and prints one table row per domain: sizes,
// iterations, time per phase and quality. Rows paste into RESULTS.md.
//
//   meshbench3d [--backend cpu|gpu] [--threads T] [--h0 H | --nodes N] [--repeat R] [-o OUT]...
//               DOMAIN...
//
// --backend gpu runs the steps on CUDA device 0 (gpu_engine3.h), the triangulations and the
// finish on the host's T threads, as the service's GPU worker does.
// DOMAIN is one of cases3d.h's names (ball, box_minus_sphere, cylinder_graded, torus). --nodes
// picks h0 so that the initial nodes number about N; -o writes each mesh, with {name} replaced
// by the domain's name (format from the extension: .msh .msh22 .vtu).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/cases3d.h"
#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh3d/assemble_mesh3d.h"
#include "core/distmesh3d/distmesh3d.h"
#include "core/distmesh3d/engine3.h"
#include "core/distmesh3d/geometry_domain3d.h"
#include "core/distmesh3d/node_estimate3d.h"
#include "core/distmesh3d/surface_offset3d.h"
#include "core/geometry3d/compile3d.h"
#include "core/mesh/mesh_file.h"
#include "core/mesh3d/tet_quality.h"
#include "core/mesh3d/tet_validity.h"
#ifdef MESHD_HAVE_CUDA
#include "kernels/gpu_engine3.h"
#endif

namespace {

struct Options {
  std::string backend = "cpu";
  unsigned threads = 0;
  double h0 = 0.0;
  double nodes = 0.0;
  int repeat = 1;
  std::vector<std::string> outputs;
  std::vector<std::string> domains;
};

[[noreturn]] void usage(int code) {
  std::fprintf(code == 0 ? stdout : stderr,
               "usage: meshbench3d [--backend cpu|gpu] [--threads T] [--h0 H | --nodes N]\n"
               "                   [--repeat R] [-o OUT]... DOMAIN...\n"
               "  DOMAIN      %s\n"
               "  --backend   where the steps run (default cpu)\n"
               "  --h0 H      the edge length (default: each domain's own)\n"
               "  --nodes N   pick h0 so that the mesh has about N nodes\n"
               "  --repeat R  mesh each domain R times and report the fastest run\n"
               "  -o OUT      write each mesh to OUT ({name} = the domain; .msh .msh22 .vtu)\n",
               meshd::bench::case3d_names().c_str());
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
    else if (a == "--h0")
      o.h0 = std::stod(value());
    else if (a == "--nodes")
      o.nodes = std::stod(value());
    else if (a == "--repeat")
      o.repeat = std::max(1, std::stoi(value()));
    else if (a == "-o")
      o.outputs.push_back(value());
    else if (!a.empty() && a[0] == '-')
      usage(2);
    else
      o.domains.push_back(a);
  }
  if (o.domains.empty() || (o.backend != "cpu" && o.backend != "gpu")) usage(2);
  return o;
}

std::string expand(std::string pattern, const std::string& name) {
  for (size_t at; (at = pattern.find("{name}")) != std::string::npos;) pattern.replace(at, 6, name);
  return pattern;
}

std::unique_ptr<meshd::Engine3> make_engine(const Options& o) {
  if (o.backend == "cpu") return nullptr;
#ifdef MESHD_HAVE_CUDA
  return std::make_unique<meshd::GpuEngine3>(0);
#else
  std::fprintf(stderr, "meshbench3d: this build has no GPU engine\n");
  std::exit(2);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  meshd::ThreadPool pool(opt.threads);
  const std::unique_ptr<meshd::Engine3> engine = make_engine(opt);
  std::printf(
      "| domain | steps, threads | h0 | nodes | tetrahedra | iterations | retri (partial, "
      "repaired) | "
      "removed / fixed "
      "unused "
      "| t_relax s (initial / triangulations [CGAL] / steps) "
      "| t_slivers s | t_total s | q_min | q_mean | q < 0.2 | min dihedral | max dihedral "
      "| surface off / h0 (max, nodes > 1e-3) | settled / caps / stuck |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  int failures = 0;
  for (const std::string& name : opt.domains) {
    try {
      const meshd::bench::Case3 c = meshd::bench::case3d(name);
      double h0 = opt.h0 > 0.0 ? opt.h0 : c.h0;
      const bool uniform = c.size.terms.empty();
      const auto size = meshd::compile_size_field3(c.size, 1.0);
      const auto program =
          std::make_shared<const meshd::Program3>(meshd::compile_geometry3(c.shape));
      if (opt.nodes > 0.0) {
        const meshd::GeometryDomain3 probe(program, h0, size, uniform, true, INFINITY);
        const meshd::Domain3& d = probe.domain();
        h0 = meshd::h0_for_node_count3d(
            meshd::survey_volume3d(d.distance, d.size, d.bounds).weighted_volume, opt.nodes);
      }
      const meshd::GeometryDomain3 geometry(program, h0, size, uniform, true, INFINITY);
      meshd::Relaxed3 best;
      for (int r = 0; r < opt.repeat; ++r) {
        meshd::Relaxed3 mesh = meshd::distmesh3d(geometry.domain(), h0, meshd::Params3{}, &pool,
                                                 nullptr, nullptr, engine.get());
        if (r == 0 || mesh.t_relax + mesh.t_slivers < best.t_relax + best.t_slivers)
          best = std::move(mesh);
      }
      const double best_relax = best.t_relax, best_slivers = best.t_slivers;
      const meshd::TetQualityStats q = meshd::summarize_tet_quality(best.points, best.tets);
      const meshd::SurfaceOffset3 off =
          meshd::surface_offset3d(geometry.domain(), best.points, best.tets, 1e-3 * h0);
      const bool converged = best.converged;
      std::printf(
          "| %s | %s, %u | %.5f | %zu | %zu | %d | %d (%d, %d, %d) | %lld / %lld | %.3f (%.3f / "
          "%.3f "
          "[%.3f] / "
          "%.3f) | "
          "%.3f | %.3f | %.3f | "
          "%.4f "
          "| %lld | %.1f | %.1f | %.1e, %lld of %lld | %lld / %lld / %lld |\n",
          name.c_str(), opt.backend.c_str(), pool.size(), h0, best.points.size(), best.tets.size(),
          best.iterations, best.retriangulations, best.partial_retriangulations,
          best.repaired_retriangulations, best.repairs_refused,
          static_cast<long long>(best.removed), static_cast<long long>(best.unused_fixed),
          best_relax, best.t_initial, best.t_triangulate, best.t_delaunay, best.t_steps,
          best_slivers, best_relax + best_slivers, q.q_min, q.q_mean,
          static_cast<long long>(q.histogram[0] + q.histogram[1]), q.min_dihedral_deg,
          q.max_dihedral_deg, off.max / h0, static_cast<long long>(off.beyond),
          static_cast<long long>(off.surface), static_cast<long long>(best.surface.moved),
          static_cast<long long>(best.surface.dropped), static_cast<long long>(best.surface.stuck));
      const meshd::TetMesh mesh = meshd::assemble_mesh3d(geometry.domain(), std::move(best));
      const meshd::TetValidityReport validity = meshd::check_tet_validity(mesh);
      if (!validity.valid()) std::printf("  INVALID: %s\n", validity.problems[0].c_str());
      if (!converged || !validity.valid()) ++failures;
      for (const std::string& out : opt.outputs) {
        const std::string file = expand(out, name);
        const auto parent = std::filesystem::path(file).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent);
        meshd::write_mesh_file(mesh, file, meshd::format_from_path(file));
      }
    } catch (const meshd::Error& e) {
      std::fprintf(stderr, "meshbench3d: %s: %s\n", name.c_str(), e.what());
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
