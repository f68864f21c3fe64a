// GpuEngine::Impl's repairs (step 3): a moved triangulation flipped back to Delaunay on the device,
// its turned triangles dropped or its folds mended, undecided tests on the host
// (gpu_engine_impl.h).
#include <vector>

#include "core/delaunay/exact_predicates.h"
#include "kernels/gpu_engine_impl.h"
#include "kernels/keep_triangles.h"

namespace meshd {

namespace {

// Undecided in-circle tests a round may hand to the host; more means a rebuild.
constexpr int32_t kMaxUndecided = 4096;
// Flip rounds launched one by one (without the device's loop) between two reads of the counters.
constexpr int kRoundsPerBatch = 8;
// A repair that needs more batches of rounds than this (kRoundsPerBatch rounds each, or in the
// loop up to flip_rounds_per_launch) is pathological: rebuild instead.
constexpr int kMaxFlipLaunches = 25;

}  // namespace

void GpuEngine::Impl::reset_counters() {
  counters.resize(1);
  MESHD_CUDA_CHECK(cudaMemsetAsync(counters.data(), 0, sizeof(gpu::TopologyCounters), stream));
}

const gpu::TopologyCounters& GpuEngine::Impl::read_counters() {
  MESHD_CUDA_CHECK(cudaMemcpyAsync(h_counters.get(), counters.data(), sizeof(gpu::TopologyCounters),
                                   cudaMemcpyDeviceToHost, stream));
  sync();
  return *h_counters.get();
}

int64_t GpuEngine::Impl::repair_folds_too(int64_t& dropped, bool& refilled) {
  const int64_t flips = repair(dropped);
  return flips >= 0 ? flips : mend_folds(refilled);
}

int64_t GpuEngine::Impl::mend_folds(bool& refilled) {
  if (!prepare_completion()) return -1;
  refilled = true;
  return flip_prepared();
}

bool GpuEngine::Impl::one_block_retriangulation() const {
  return one_block_topology && gpu::bars_fit_one_block(static_cast<int64_t>(tris.size()), n);
}

void GpuEngine::Impl::launch_repair_and_bars() {
  const auto m = static_cast<int64_t>(tris.size());
  size_filter(m);
  size_bars(3 * m);
  scale_lagged_ok = false;
  launch_repair();
  bars_in_one_block(totals.data() + 2, counters.data());
}

TopologyStats GpuEngine::Impl::end_one_block_repair() {
  const gpu::TopologyCounters c = *h_counters.get();
  const bool built = gpu::settled_on_device(c);
  one_read_retriangulations += built;
  TopologyStats stats;
  stats.full = false;
  int64_t flips = finish_repair(c, stats.dropped);
  if (built) keep.resize(static_cast<int64_t>(tris.size()));  // the same memory
  if (flips < 0) flips = mend_folds(stats.folds_refilled);
  if (flips < 0) {
    stats.full = true;
    stats.repair_failed = true;
  } else {
    stats.flips = flips;
  }
  return end_retriangulation(stats, built);
}

TopologyStats GpuEngine::Impl::end_retriangulation(TopologyStats stats, bool bars_built) {
  if (stats.full) full_triangulation();
  if (completion_failed) stats.repair_failed = true;
  completion_failed = false;
  have_triangulation = true;
  const TopologyStats sizes = bars_built ? bars_sizes() : filter_and_bars();
  stats.triangles = sizes.triangles;
  stats.bars = sizes.bars;
  return stats;
}

int64_t GpuEngine::Impl::repair(int64_t& dropped) {
  launch_repair();
  return finish_repair(read_counters(), dropped);
}

void GpuEngine::Impl::launch_repair() {
  const auto m = static_cast<int64_t>(tris.size());
  flags.resize(m);
  if (small_topology()) {
    position.resize(m);
    tris_tmp.resize(m);
    nbrs_tmp.resize(m);
    totals.resize(3);
    gpu::launch_repair_and_keep_in_one_block(
        flip_views(flags.span()), flip_batch.data(),
        {.check = {keep.span(), on_boundary.span(), flags.span()},
         .position = position.span(),
         .tris_out = tris_tmp.span(),
         .nbrs_out = nbrs_tmp.span(),
         .live = totals.data() + 2},
        stream);
  } else {
    begin_flips(flags.span());
    gpu::launch_check_orientation(p.span(), tris.span(), keep.span(), on_boundary.span(),
                                  flags.span(), counters.data(), stream);
    run_flip_rounds(true);
  }
}

int64_t GpuEngine::Impl::finish_repair(const gpu::TopologyCounters c, int64_t& dropped) {
  if (c.fatal > 0) return -1;
  dropped = c.dropped;
  const int64_t alive = static_cast<int64_t>(tris.size()) - c.dropped;
  if (small_topology() && gpu::settled_on_device(c)) {
    // Removed in the repair's launch, which reset their flipped_round too.
    for (DeviceBuffer<Tri>* t : {&tris, &nbrs}) t->resize(alive);  // the same memory
    if (c.dropped > 0) flipped_round.resize(alive);
    return c.flips;
  }
  const int64_t flips = settle_flips(c);
  if (flips < 0 || c.dropped == 0) return flips;
  // The check counted every triangle it flagged: no wait for the count.
  gpu::keep_triangles(flags.span(), tris, nbrs, {position, tris_tmp, nbrs_tmp}, temp, stream,
                      alive);
  flipped_round.resize(alive);
  MESHD_CUDA_CHECK(cudaMemsetAsync(flipped_round.data(), 0xff, alive * sizeof(int32_t), stream));
  return flips;
}

int64_t GpuEngine::Impl::flip_to_delaunay() {
  begin_flips();
  run_flip_rounds(true);
  return settle_flips(read_counters());
}

void GpuEngine::Impl::begin_flips(gpu::DeviceSpan<const uint8_t> walls) {
  gpu::launch_begin_flips(flip_views(walls), flip_batch.data(), stream);
}

gpu::FlipBatch GpuEngine::Impl::flip_views(gpu::DeviceSpan<const uint8_t> walls) {
  const int64_t mt = static_cast<int64_t>(tris.size());
  vote.resize(mt);
  partner.resize(mt);
  undecided.resize(kMaxUndecided);
  gpu::size_flip_lists(flip_lists, mt);
  counters.resize(1);
  // The repair's views for the flip rounds (flip_round.h); its first round tests every edge.
  gpu::FlipBatch b{};
  b.p = p.span();
  b.tris = tris.span();
  b.nbrs = nbrs.span();
  b.vote = vote.span();
  b.flipped_round = flipped_round.span();
  b.partner = partner.span();
  b.undecided = undecided.span();
  b.walls = walls;
  b.counters = counters.data();
  for (int k = 0; k < 2; ++k) {
    b.work[k] = flip_lists.work[k].data();
    b.work_stamp[k] = flip_lists.work_stamp[k].data();
  }
  b.voted = flip_lists.voted.data();
  b.voted_stamp = flip_lists.voted_stamp.data();
  b.rounds_per_launch = flip_rounds_per_launch;
  b.tail_items = flip_tail_items;
  b.full = 1;
  return b;
}

int64_t GpuEngine::Impl::settle_flips(gpu::TopologyCounters rc) {
  for (int launches = 1;; ++launches) {
    if (rc.undecided > kMaxUndecided) return -1;
    if (rc.undecided == 0 && rc.candidates == 0) return rc.flips;
    if (rc.undecided > 0) {
      // The rounds' lists are stale after their last flips: one round again, testing every
      // edge, with the host deciding what the filter could not.
      gpu::launch_full_flip_candidates(flip_batch.data(), step_wave, stream);
      const gpu::TopologyCounters again = read_counters();
      if (again.undecided > kMaxUndecided) return -1;
      const int32_t to_flip = again.undecided > 0 ? decide_on_host(again.undecided) : 0;
      // Exactly co-circular quadruples stay undecided for the filter: once the host says
      // that none of them flips and nothing else does, the triangulation is Delaunay.
      if (again.candidates == 0 && to_flip == 0) return again.flips;
      gpu::launch_flips(flip_batch.data(), step_wave, stream);
      unsettle();  // the host's flips may make new candidates, however few the round found
    }
    if (launches == kMaxFlipLaunches) return -1;
    // Rounds back to back, read once: repairs cascade through a dozen rounds of a few flips
    // each, and a host round trip per round would cost more than the flips.
    run_flip_rounds(false);
    rc = read_counters();
  }
}

void GpuEngine::Impl::run_flip_rounds(bool first) {
  if (small_topology()) {
    gpu::launch_flip_rounds_in_one_block(flip_batch.data(), stream);
    return;
  }
  const int rounds_by_kernels = flip_loop_blocks == 0 ? kRoundsPerBatch : first ? 1 : 0;
  for (int r = 0; r < rounds_by_kernels; ++r) {
    gpu::launch_flip_candidates(flip_batch.data(), step_wave, stream);
    gpu::launch_flips(flip_batch.data(), step_wave, stream);
  }
  if (flip_loop_blocks > 0) gpu::launch_flip_loop(flip_batch.data(), flip_loop_blocks, stream);
}

bool GpuEngine::Impl::small_topology() const {
  return one_block_topology && static_cast<int64_t>(tris.size()) <= gpu::kOneBlockRows;
}

void GpuEngine::Impl::unsettle() {
  MESHD_CUDA_CHECK(cudaMemsetAsync(&counters.data()->checked, 0, 2 * sizeof(int32_t), stream));
}

int32_t GpuEngine::Impl::decide_on_host(int32_t undecided_count) {
  // Only the tests' points cross: reading every point and triangle for each batch of
  // undecided tests cost the gear at 4M nodes 12.7 of its 14.5 seconds (co-circular nodes
  // along its teeth's straight sides leave hundreds of batches).
  std::vector<int32_t> ids(undecided_count);
  std::vector<gpu::InCircleTest> tests(undecided_count);
  in_circle_tests.resize(undecided_count);
  gpu::launch_gather_in_circle_tests(p.span(), tris.span(), nbrs.span(),
                                     {undecided.data(), undecided_count}, in_circle_tests.span(),
                                     stream);
  MESHD_CUDA_CHECK(cudaMemcpyAsync(ids.data(), undecided.data(), undecided_count * sizeof(int32_t),
                                   cudaMemcpyDeviceToHost, stream));
  in_circle_tests.download(tests.data(), stream);
  sync();
  std::vector<int32_t> flip_ids;
  for (int32_t i = 0; i < undecided_count; ++i) {
    const gpu::InCircleTest& q = tests[i];
    if (in_circle_sign(q.a, q.b, q.c, q.d) > 0) flip_ids.push_back(ids[i]);
  }
  decided.upload(flip_ids.data(), flip_ids.size(), stream);
  gpu::launch_vote_edges(flip_batch.data(), decided.span(), stream);
  sync();  // flip_ids is a host vector
  return static_cast<int32_t>(flip_ids.size());
}

}  // namespace meshd
