// GpuEngine::Impl's filter, bars and CSR (step 3's end): in one block's launch, as a replayed
// graph, or as the kernels one by one (gpu_engine_impl.h).
#include <vector>

#include "kernels/gpu_engine_impl.h"
#include "kernels/scan.h"

namespace meshd {

TopologyStats GpuEngine::Impl::filter_and_bars() {
  const int64_t m = static_cast<int64_t>(tris.size());
  const bool one_block = one_block_topology && gpu::bars_fit_one_block(m, n);
  const bool replayed = !one_block && m <= replayed_triangles;
  const int64_t rows = replayed ? padded_rows(m) : m;
  tris.reserve(rows, stream);
  nbrs.reserve(rows, stream);
  size_filter(rows);
  scale_lagged_ok = false;
  if (one_block) {
    size_bars(3 * m);
    bars_in_one_block();
  } else {
    size_kernels_scratch(rows);
    *h_live.get() = m;
    if (replayed) {
      size_bars(3 * rows);
      bars_graph.run([&] { return bars_key(rows); },
                     [&](cudaStream_t) {
                       filter(rows);
                       bars_and_csr(rows);
                     },
                     stream);
    } else {
      filter(rows);
      read_totals(1);
      sync();
      size_bars((*h_totals.get())[0]);
      bars_and_csr(rows);
    }
  }
  // The device idle at the end: with the CSR's sort still running as the steps begin, memcheck
  // reports garbage reads inside the step graph, unexplained (bench/RESULTS.md, 2026-11-28).
  sync();
  keep.resize(m);  // the same memory
  return bars_sizes();
}

void GpuEngine::Impl::bars_in_one_block(const int64_t* live,
                                        const gpu::TopologyCounters* repair_counters) {
  gpu::launch_filter_and_bars(
      {.p = p.span(),
       .tris = tris.span(),
       .nbrs = nbrs.span(),
       .filter = {clearance.span(), clear, fd, nested_index, problem->params.geps * problem->h0},
       .keep = keep.span(),
       .ticket = last_block_ticket.data(),
       .bars = bars.span(),
       .csr_offset = csr_offset.span(),
       .csr_entry = csr_entry.span(),
       .csr_other = csr_other.span(),
       .p_old = p_old.span(),
       .totals = totals.data(),
       .live = live,
       .host_totals = h_totals.get()->data(),
       .counters = repair_counters,
       .host_counters = repair_counters ? h_counters.get() : nullptr},
      stream);
}

int64_t GpuEngine::Impl::padded_rows(int64_t m) {
  int64_t step = 256;
  while (step * 32 <= m) step *= 2;
  return (m + step - 1) / step * step;
}

TopologyStats GpuEngine::Impl::bars_sizes() {
  TopologyStats stats;
  stats.bars = (*h_totals.get())[0];
  stats.triangles = (*h_totals.get())[1];
  size_bars(stats.bars);
  return stats;
}

void GpuEngine::Impl::size_filter(int64_t rows) {
  keep.resize(rows);
  totals.resize(3);
  csr_offset.resize(n + 1);
}

void GpuEngine::Impl::size_kernels_scratch(int64_t rows) {
  count.resize(rows);
  position.resize(rows);
  degree.resize(n + 1);
}

void GpuEngine::Impl::size_bars(int64_t room) {
  bars.resize(room);
  for (DeviceBuffer<int32_t>* end : {&csr_entry, &csr_other}) end->resize(2 * room);
}

gpu::DeviceSpan<const Tri> GpuEngine::Impl::rows_of(const DeviceBuffer<Tri>& t,
                                                    int64_t rows) const {
  return {t.data(), rows};
}

void GpuEngine::Impl::filter(int64_t rows) {
  int64_t* live = totals.data() + 2;
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(live, h_live.get(), sizeof(int64_t), cudaMemcpyHostToDevice, stream));
  gpu::launch_centroid_filter(p.span(), clearance.span(), clear, rows_of(tris, rows), fd,
                              nested_index, problem->params.geps * problem->h0, keep.span(), live,
                              stream);
  gpu::launch_count_bars(rows_of(nbrs, rows), keep.span(), count.span(), live, stream);
  gpu::exclusive_scan(count.data(), position.data(), rows, temp, stream);
  gpu::launch_scan_total(position.data(), count.data(), rows, totals.data(), stream);
}

void GpuEngine::Impl::bars_and_csr(int64_t rows) {
  gpu::launch_write_bars(rows_of(tris, rows), rows_of(nbrs, rows), keep.span(), position.span(),
                         bars.span(), totals.data() + 2, stream);
  // Rows filled by counting, not by sorting the ends: a sort cost a 20k-node job's repair 34
  // of its ~180 us (bench/RESULTS.md, 2026-11-28).
  MESHD_CUDA_CHECK(cudaMemsetAsync(degree.data(), 0, (n + 1) * sizeof(int32_t), stream));
  gpu::launch_count_bar_ends(bars.span(), totals.data(), degree.span(), stream);
  gpu::exclusive_scan(degree.data(), csr_offset.data(), n + 1, temp, stream);
  gpu::launch_fill_csr(bars.span(), totals.data(), csr_offset.span(), degree.span(),
                       csr_entry.span(), csr_other.span(), stream);
  MESHD_CUDA_CHECK(
      cudaMemcpyAsync(p_old.data(), p.data(), n * sizeof(Vec2), cudaMemcpyDeviceToDevice, stream));
  // Kept triangles, for the stats: position is free again once the bars are written.
  gpu::exclusive_scan(keep.data(), position.data(), rows, temp, stream);
  gpu::launch_scan_total(position.data(), keep.data(), rows, totals.data() + 1, stream);
  read_totals(2);
}

void GpuEngine::Impl::read_totals(int slots) {
  MESHD_CUDA_CHECK(cudaMemcpyAsync(h_totals.get()->data(), totals.data(), slots * sizeof(int64_t),
                                   cudaMemcpyDeviceToHost, stream));
}

gpu::ReplayGraph::Key GpuEngine::Impl::bars_key(int64_t rows) const {
  const auto at = [](const void* ptr) { return reinterpret_cast<uint64_t>(ptr); };
  return {epoch,
          static_cast<uint64_t>(n),
          static_cast<uint64_t>(rows),
          at(p.data()),
          at(p_old.data()),
          at(clearance.data()),
          at(tris.data()),
          at(nbrs.data()),
          at(keep.data()),
          at(count.data()),
          at(position.data()),
          at(totals.data()),
          at(bars.data()),
          at(csr_entry.data()),
          at(csr_other.data()),
          at(degree.data()),
          at(csr_offset.data()),
          at(temp.data())};
}

}  // namespace meshd
