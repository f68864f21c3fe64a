// keep_triangles against the host's compaction, on both sides of the size that one block
// compacts alone (kOneBlockRows), with the count given and read back. Skips with a message where
// no CUDA device is visible (CI).
#include "kernels/keep_triangles.h"

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

struct Linked {
  std::vector<Tri> tris, nbrs;
};

// The kept triangles in order, each link renumbered or -1 where the neighbour went.
Linked host_keep(const Linked& in, const std::vector<uint8_t>& keep) {
  std::vector<int32_t> position(in.tris.size(), -1);
  int32_t kept = 0;
  for (size_t t = 0; t < in.tris.size(); ++t)
    if (keep[t]) position[t] = kept++;
  Linked out;
  for (size_t t = 0; t < in.tris.size(); ++t) {
    if (!keep[t]) continue;
    Tri n;
    for (int k = 0; k < 3; ++k) {
      const int32_t u = in.nbrs[t].v[k];
      n.v[k] = u < 0 ? -1 : position[u];
    }
    out.tris.push_back(in.tris[t]);
    out.nbrs.push_back(n);
  }
  return out;
}

void expect_keep_matches_the_host(int64_t m, bool count_given, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> vertex(0, 1 << 20), link(-1, static_cast<int32_t>(m) - 1);
  std::bernoulli_distribution kept(0.9);
  Linked in;
  std::vector<uint8_t> keep(m);
  int64_t count = 0;
  for (int64_t t = 0; t < m; ++t) {
    in.tris.push_back(Tri{{vertex(rng), vertex(rng), vertex(rng)}});
    in.nbrs.push_back(Tri{{link(rng), link(rng), link(rng)}});
    keep[t] = kept(rng);
    count += keep[t];
  }
  const Linked want = host_keep(in, keep);
  cudaStream_t stream = nullptr;
  DeviceBuffer<Tri> tris, nbrs, tris_tmp, nbrs_tmp;
  DeviceBuffer<uint8_t> d_keep, temp;
  DeviceBuffer<int32_t> position;
  tris.upload(in.tris.data(), m, stream);
  nbrs.upload(in.nbrs.data(), m, stream);
  d_keep.upload(keep.data(), m, stream);
  const int64_t got_count =
      gpu::keep_triangles(d_keep.span(), tris, nbrs, {position, tris_tmp, nbrs_tmp}, temp, stream,
                          count_given ? count : -1);
  ASSERT_EQ(got_count, count);
  ASSERT_EQ(static_cast<int64_t>(tris.size()), count);
  Linked got;
  got.tris.resize(count);
  got.nbrs.resize(count);
  tris.download(got.tris.data(), stream);
  nbrs.download(got.nbrs.data(), stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  for (int64_t t = 0; t < count; ++t) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(got.tris[t].v[k], want.tris[t].v[k]) << "triangle " << t;
      ASSERT_EQ(got.nbrs[t].v[k], want.nbrs[t].v[k]) << "triangle " << t;
    }
  }
}

TEST(GpuKeepTriangles, CompactionsMatchTheHostAroundTheOneBlockSize) {
  SKIP_WITHOUT_GPU();
  const int64_t one_block = gpu::kOneBlockRows;
  uint32_t seed = 1;
  for (int64_t m :
       {int64_t{1}, int64_t{1000}, one_block - 1, one_block, one_block + 1, 3 * one_block}) {
    SCOPED_TRACE(m);
    for (bool count_given : {true, false}) expect_keep_matches_the_host(m, count_given, seed++);
  }
}

}  // namespace
}  // namespace meshd
