// StarTable: the stars of the nodes asked for, each with its triangles in increasing order, the
// same for any number of threads and however the requests are split.
#include "core/distmesh/star_table.h"

#include <gtest/gtest.h>

#include "core/common/thread_pool.h"

namespace meshd {
namespace {

// A strip of 2 k triangles over the nodes 0..k+1, each node in up to three of them, the
// triangles numbered so that the chunks of the scan see each star in several pieces.
std::vector<std::array<int32_t, 3>> strip(int32_t k) {
  std::vector<std::array<int32_t, 3>> t;
  for (int32_t i = 0; i < k; ++i) t.push_back({i, i + 1, i + 2});
  for (int32_t i = k - 1; i >= 0; --i) t.push_back({i + 2, i + 1, i});
  return t;
}

std::vector<int32_t> brute_force_star(const std::vector<std::array<int32_t, 3>>& t, int32_t v) {
  std::vector<int32_t> out;
  for (size_t i = 0; i < t.size(); ++i)
    for (int32_t u : t[i])
      if (u == v) out.push_back(static_cast<int32_t>(i));
  return out;
}

TEST(StarTable, TheTrianglesAroundEachNodeAskedForInIncreasingOrder) {
  const int32_t k = 100000;  // several chunks of the scan
  const auto triangles = strip(k);
  for (unsigned threads : {1u, 3u}) {
    ThreadPool pool(threads);
    StarTable stars(k + 2, triangles, &pool);
    const std::vector<int32_t> first = {7, 0, 99999, 7}, second = {3, 0, k + 1, 50000};
    stars.add(first);
    EXPECT_FALSE(stars.has(3));
    stars.add(second);
    for (int32_t v : {0, 3, 7, 50000, 99999, k + 1}) {
      ASSERT_TRUE(stars.has(v)) << v;
      EXPECT_EQ(std::vector<int32_t>(stars.begin(v), stars.end(v)), brute_force_star(triangles, v))
          << "node " << v << ", " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace meshd
