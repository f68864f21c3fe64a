// The bars' CSR by node on the device (launch_count_bar_ends, launch_fill_csr) against the host's
// stable ordering: each node's row holds its bar ends in increasing order, whatever order the
// device's atomics placed them in, for rows short and long, with room past the bar count left
// out. Skips with a message where no CUDA device is visible (CI).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "kernels/cuda_check.h"
#include "kernels/device_buffer.h"
#include "kernels/launch.h"
#include "kernels/scan.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

using gpu::Bar;
using gpu::DeviceBuffer;

struct Csr {
  std::vector<int32_t> offset, entry, other;
};

// Row i: the ends 2b + e with end e of bars[b] at node i, in increasing order.
Csr host_csr(const std::vector<Bar>& bars, int32_t n) {
  Csr c;
  std::vector<std::vector<int32_t>> rows(n);
  for (size_t b = 0; b < bars.size(); ++b) {
    rows[bars[b].a].push_back(static_cast<int32_t>(2 * b));
    rows[bars[b].b].push_back(static_cast<int32_t>(2 * b + 1));
  }
  c.offset.push_back(0);
  for (const auto& row : rows) {
    for (int32_t e : row) {
      c.entry.push_back(e);
      c.other.push_back((e & 1) ? bars[e >> 1].a : bars[e >> 1].b);
    }
    c.offset.push_back(static_cast<int32_t>(c.entry.size()));
  }
  return c;
}

Csr device_csr(const std::vector<Bar>& bars, int64_t room, int32_t n) {
  cudaStream_t stream = nullptr;
  std::vector<Bar> padded = bars;
  padded.resize(room, Bar{0, 1});  // what the room holds must not count
  const int64_t count = static_cast<int64_t>(bars.size());
  DeviceBuffer<Bar> d_bars;
  DeviceBuffer<int64_t> d_count;
  DeviceBuffer<int32_t> degree, offset, entry, other;
  DeviceBuffer<uint8_t> temp;
  d_bars.upload(padded.data(), padded.size(), stream);
  d_count.upload(&count, 1, stream);
  degree.resize(n + 1);
  offset.resize(n + 1);
  entry.resize(2 * room);
  other.resize(2 * room);
  MESHD_CUDA_CHECK(cudaMemsetAsync(degree.data(), 0, (n + 1) * sizeof(int32_t), stream));
  gpu::launch_count_bar_ends(d_bars.span(), d_count.data(), degree.span(), stream);
  gpu::exclusive_scan(degree.data(), offset.data(), n + 1, temp, stream);
  gpu::launch_fill_csr(d_bars.span(), d_count.data(), offset.span(), degree.span(), entry.span(),
                       other.span(), stream);
  Csr c;
  c.offset.resize(n + 1);
  c.entry.resize(2 * room);
  c.other.resize(2 * room);
  std::vector<int32_t> left(n + 1);
  offset.download(c.offset.data(), stream);
  entry.download(c.entry.data(), stream);
  other.download(c.other.data(), stream);
  degree.download(left.data(), stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  c.entry.resize(2 * count);
  c.other.resize(2 * count);
  EXPECT_TRUE(std::all_of(left.begin(), left.end(), [](int32_t d) { return d == 0; }))
      << "degree should count down to zero";
  return c;
}

TEST(GpuBarCsr, RowsHoldTheirEndsInOrderShortAndLong) {
  SKIP_WITHOUT_GPU();
  const int32_t n = 3000;
  std::vector<Bar> bars;
  // A fan of 40 (sorted in place), one of 12 (the 16-wide registers), a chain (rows of two).
  for (int32_t i = 1; i <= 40; ++i) bars.push_back({0, i});
  for (int32_t i = 42; i <= 53; ++i) bars.push_back({i, 41});
  for (int32_t i = 100; i < 1100; ++i) bars.push_back({i, i + 1});
  std::mt19937 rng(7);
  std::uniform_int_distribution<int32_t> node(60, n - 1);
  for (int k = 0; k < 5000; ++k) {
    const int32_t a = node(rng), b = node(rng);
    if (a != b) bars.push_back({a, b});
  }
  std::shuffle(bars.begin() + 40, bars.end(), rng);
  const Csr want = host_csr(bars, n);
  for (int64_t room : {static_cast<int64_t>(bars.size()), static_cast<int64_t>(bars.size()) + 77}) {
    const Csr got = device_csr(bars, room, n);
    EXPECT_EQ(got.offset, want.offset) << "room " << room;
    EXPECT_EQ(got.entry, want.entry) << "room " << room;
    EXPECT_EQ(got.other, want.other) << "room " << room;
  }
}

}  // namespace
}  // namespace meshd
