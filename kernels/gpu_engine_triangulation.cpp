// GpuEngine::Impl's triangulations from scratch (step 3): the device's point insertion, the
// initial lattice's, CGAL where those fail, and the completion of surviving triangles
// (gpu_engine_impl.h).
#include <vector>

#include "core/delaunay/delaunay.h"
#include "kernels/gpu_engine_impl.h"
#include "kernels/keep_triangles.h"
#include "kernels/scan.h"

namespace meshd {

int64_t GpuEngine::Impl::compact_alive_triangles(const DeviceBuffer<uint8_t>& alive) {
  const int64_t m = static_cast<int64_t>(tris.size());
  count.resize(m);
  gpu::exclusive_scan(alive.data(), count.data(), m, temp, stream);
  const int64_t kept = gpu::scan_total(count.data(), alive.data(), m, stream);
  tris_tmp.resize(kept);
  nbrs_tmp.resize(kept);
  gpu::launch_compact_triangles(tris.span(), nbrs.span(), alive.span(), count.span(),
                                tris_tmp.span(), nbrs_tmp.span(), stream);
  return kept;
}

bool GpuEngine::Impl::prepare_completion() {
  // A survivor or a split triangle may have turned over: cut out first, the fold then filled
  // with the gaps.
  const bool folded = gpu::cut_folds(p.span(), tris, nbrs, gaps, temp, stream);
  prepared = (!folded && covers_hull()) ||
             gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream) ||
             complete_from_domain_triangles();
  prepared_checked = false;
  completion_failed = !prepared;
  return prepared;
}

bool GpuEngine::Impl::complete_from_domain_triangles() {
  keep.resize(tris.size());  // scratch: the next triangulation sets it again
  gpu::launch_centroid_filter(p.span(), clearance.span(), clear, tris.span(), fd, nested_index,
                              problem->params.geps * problem->h0, keep.span(), nullptr, stream);
  gpu::keep_triangles(keep.span(), tris, nbrs, {position, tris_tmp, nbrs_tmp}, temp, stream);
  return gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream);
}

std::vector<Vec2> GpuEngine::Impl::download_points() {
  std::vector<Vec2> host(n);
  p.download(host.data(), stream);
  sync();
  return host;
}

void GpuEngine::Impl::full_triangulation() {
  if (triangulate_on_device()) return;
  const Triangulation dt = delaunay_triangulate(download_points());
  static_assert(sizeof(Tri) == sizeof(std::array<int32_t, 3>));
  tris.upload(reinterpret_cast<const Tri*>(dt.triangles.data()), dt.triangles.size(), stream);
  nbrs.upload(reinterpret_cast<const Tri*>(dt.neighbors.data()), dt.neighbors.size(), stream);
  flipped_round.resize(tris.size());
  MESHD_CUDA_CHECK(
      cudaMemsetAsync(flipped_round.data(), 0xff, flipped_round.size() * sizeof(int32_t), stream));
}

bool GpuEngine::Impl::triangulate_on_device() {
  last_insertion = gpu::insert_points(p.span(), tris, nbrs, insertion, temp, stream);
  // Every triangle is counter-clockwise by the insertion's exact predicates, and the gaps' by
  // CGAL's: the flips need no orientation check.
  prepared = covers_hull() || gpu::complete_gaps(p.span(), nfix, tris, nbrs, gaps, temp, stream);
  prepared_checked = prepared;
  return prepared && flip_prepared() >= 0;
}

void GpuEngine::Impl::prepare(const InitialGrid& grid) {
  prepared = gpu::lattice_triangulation(grid, flags.span(), position.span(), nfix, p.span(), tris,
                                        nbrs, lattice, gaps, temp, stream);
  prepared_checked = prepared;
}

int64_t GpuEngine::Impl::flip_prepared() {
  prepared = false;
  const int64_t m = static_cast<int64_t>(tris.size());
  keep.resize(m);  // every triangle counts: any that turned over calls for a rebuild
  MESHD_CUDA_CHECK(cudaMemsetAsync(keep.data(), 1, m, stream));
  flipped_round.resize(m);
  MESHD_CUDA_CHECK(cudaMemsetAsync(flipped_round.data(), 0xff, m * sizeof(int32_t), stream));
  // No orientation check for the lattice: the host checked every triangle with exact
  // predicates, and flat pockets along lattice lines would leave the device's filter undecided.
  if (prepared_checked) return flip_to_delaunay();
  int64_t dropped = 0;
  return repair(dropped);
}

bool GpuEngine::Impl::covers_hull() {
  const int64_t m = static_cast<int64_t>(tris.size());
  next.resize(n);
  reset_counters();
  gpu::launch_hull_links(tris.span(), nbrs.span(), next.span(), counters.data(), stream);
  gpu::launch_hull_turns(p.span(), tris.span(), nbrs.span(), next.span(), counters.data(), stream);
  const gpu::TopologyCounters c = read_counters();
  // hull_links counts boundary edges in `candidates`, hull_turns right turns in `fatal`.
  return c.fatal == 0 && m == 2 * n - 2 - c.candidates;
}

}  // namespace meshd
