// GpuEngine::Impl's problem and node set: the programs on the device, the nodes' state, and the
// removal of nodes (gpu_engine_impl.h).
#include <utility>
#include <vector>

#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "kernels/gpu_engine_impl.h"
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"

namespace meshd {

void GpuEngine::Impl::load_problem(const CompiledProblem& prob) {
  problem = &prob;
  ++epoch;
  copy_tidy = false;
  geometry_code.upload(prob.geometry.code.data(), prob.geometry.code.size(), stream);
  geometry_params.upload(prob.geometry.params.data(), prob.geometry.params.size(), stream);
  size_code.upload(prob.size.shapes.code.data(), prob.size.shapes.code.size(), stream);
  size_params.upload(prob.size.shapes.params.data(), prob.size.shapes.params.size(), stream);
  geometry_nodes.upload(prob.geometry.nodes.data(), prob.geometry.nodes.size(), stream);
  size_nodes.upload(prob.size.shapes.nodes.data(), prob.size.shapes.nodes.size(), stream);
  geometry_samples.upload(prob.geometry.samples.data(), prob.geometry.samples.size(), stream);
  size_samples.upload(prob.size.shapes.samples.data(), prob.size.shapes.samples.size(), stream);
  size_terms.upload(prob.size.terms.data(), prob.size.terms.size(), stream);
  fd = {geometry_code.data(), static_cast<uint32_t>(prob.geometry.code.size()),
        geometry_params.data(), geometry_nodes.data(), geometry_samples.data()};
  fh = {{size_code.data(), static_cast<uint32_t>(prob.size.shapes.code.size()), size_params.data(),
         size_nodes.data(), size_samples.data()},
        size_terms.data(),
        static_cast<uint32_t>(prob.size.terms.size())};
  uniform = prob.size.uniform();
  nested_index = nests_indexed_unions(prob.geometry);
  nfix = static_cast<int64_t>(prob.fixed_points.size());
  fixed.upload(prob.fixed_points.data(), prob.fixed_points.size(), stream);
}

void GpuEngine::Impl::reset_node_state() {
  ++epoch;
  p_next.resize(n);
  p_old.resize(n);
  velocity.resize(n);
  on_boundary.resize(n);
  clearance.resize(n);
  if (n > 0) {
    MESHD_CUDA_CHECK(cudaMemsetAsync(p_old.data(), 0x7f, n * sizeof(Vec2), stream));  // ~1e306
    MESHD_CUDA_CHECK(cudaMemsetAsync(velocity.data(), 0, n * sizeof(Vec2), stream));
    MESHD_CUDA_CHECK(cudaMemsetAsync(on_boundary.data(), 0, n, stream));
    // Zero: unknown, evaluated at the next step.
    MESHD_CUDA_CHECK(cudaMemsetAsync(clearance.data(), 0, n * sizeof(float), stream));
  }
  clear = ClearanceRule::make(problem->lipschitz, problem->params.geps * problem->h0,
                              kNearBoundaryRelative * problem->h0, problem->h0);
  // Fixed nodes never move: classify them once, on the host.
  std::vector<uint8_t> fixed_boundary(nfix);
  const double near = kNearBoundaryRelative * problem->h0;
  for (int64_t f = 0; f < nfix; ++f)
    fixed_boundary[f] = eval_sdf(problem->geometry.view(), problem->fixed_points[f]) >= -near;
  if (nfix > 0)
    MESHD_CUDA_CHECK(cudaMemcpyAsync(on_boundary.data(), fixed_boundary.data(), nfix,
                                     cudaMemcpyHostToDevice, stream));
  have_triangulation = false;
  prepared = false;
  scale_lagged_ok = false;
  bars.resize(0);
  sync();  // fixed_boundary is a stack buffer
}

int64_t GpuEngine::Impl::compact_nodes(int64_t max_removed) {
  position.resize(n);
  gpu::exclusive_scan(flags.data(), position.data(), n, temp, stream);
  const int64_t kept = gpu::scan_total(position.data(), flags.data(), n, stream);
  if (kept == n || n - kept > max_removed) return 0;
  // The triangles untouched by the removal survive, renumbered, with their links: the next
  // full triangulation completes them (complete_gaps.h) instead of starting over.
  bool survived = false;
  if (have_triangulation) {
    // keep serves as scratch: the next triangulation sets it again.
    keep.resize(tris.size());
    gpu::launch_surviving_triangles(tris.span(), flags.span(), keep.span(), stream);
    survived =
        gpu::keep_triangles(keep.span(), tris, nbrs, {count, tris_tmp, nbrs_tmp}, temp, stream) > 0;
    gpu::launch_renumber_vertices(tris.span(), position.span(), stream);
  }
  gpu::launch_compact_points(p.span(), flags.span(), position.span(), p_next.span(), stream);
  std::swap(p, p_next);
  const int64_t removed = n - kept;
  n = kept;
  p.resize(n);
  reset_node_state();
  if (survived) prepare_completion();
  return removed;
}

}  // namespace meshd
