// The device's exclusive scans against the host's, on both sides of the size that one block
// scans alone, for flags and for counts. Skips with a message where no CUDA device is visible
// (CI).
#include "kernels/scan.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "kernels/cuda_check.h"
#include "kernels/device_buffer.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

using gpu::DeviceBuffer;

template <typename In>
void expect_scan_matches_the_host(int64_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, sizeof(In) == 1 ? 1 : 9);
  std::vector<In> in(n);
  for (In& v : in) v = static_cast<In>(value(rng));
  std::vector<int32_t> want(n);
  int32_t sum = 0;
  for (int64_t i = 0; i < n; ++i) {
    want[i] = sum;
    sum += in[i];
  }
  cudaStream_t stream = nullptr;
  DeviceBuffer<In> d_in;
  DeviceBuffer<int32_t> d_out;
  DeviceBuffer<uint8_t> temp;
  d_in.upload(in.data(), in.size(), stream);
  d_out.resize(n);
  gpu::exclusive_scan(d_in.data(), d_out.data(), n, temp, stream);
  std::vector<int32_t> got(n);
  d_out.download(got.data(), stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  EXPECT_EQ(got, want) << "n " << n;
  EXPECT_EQ(gpu::scan_total(d_out.data(), d_in.data(), n, stream), sum) << "n " << n;
}

TEST(GpuScan, ExclusiveScansMatchTheHostAroundTheOneBlockSize) {
  SKIP_WITHOUT_GPU();
  for (int64_t n : {1, 7, 512, 8191, 8192, 8193, 20000, 32767, 32768, 32769, 100000}) {
    expect_scan_matches_the_host<uint8_t>(n, static_cast<uint32_t>(n));
    expect_scan_matches_the_host<int32_t>(n, static_cast<uint32_t>(n) + 1);
  }
}

}  // namespace
}  // namespace meshd
