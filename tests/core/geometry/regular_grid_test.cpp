// Regular grids (regular_grid.h): bilinear interpolation reproduces what it should exactly, the
// border extends outwards, and grids appended to one program keep their own samples.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/geometry/program.h"
#include "core/geometry/regular_grid.h"

namespace meshd {
namespace {

// f(x, y) = a + b x + c y + d x y: bilinear in every cell, so interpolation must return it.
double bilinear_function(Vec2 p) { return 0.25 + 0.5 * p.x - 0.75 * p.y + 0.125 * p.x * p.y; }

std::vector<float> sample(Vec2 origin, Vec2 spacing, uint32_t nx, uint32_t ny,
                          double (*f)(Vec2)) {
  std::vector<float> v(size_t(nx) * ny);
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i)
      v[size_t(j) * nx + i] =
          static_cast<float>(f({origin.x + i * spacing.x, origin.y + j * spacing.y}));
  return v;
}

TEST(RegularGrid, ReproducesABilinearFunctionInsideAndTheBorderOutside) {
  // Coordinates chosen so that the samples are exact in single precision.
  const Vec2 origin{-1.0, 2.0}, spacing{0.5, 0.25};
  const uint32_t nx = 9, ny = 5;
  const auto values = sample(origin, spacing, nx, ny, bilinear_function);
  const RegularGrid g{origin, spacing, nx, ny, values.data()};
  EXPECT_DOUBLE_EQ(g.box().max.x, 3.0);
  EXPECT_DOUBLE_EQ(g.box().max.y, 3.0);

  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-1.0, 3.0), y(2.0, 3.0);
  for (int k = 0; k < 1000; ++k) {
    const Vec2 p{x(rng), y(rng)};
    EXPECT_NEAR(bilinear(g, p), bilinear_function(p), 1e-12) << p.x << " " << p.y;
  }
  // Every sample is returned as it is, the last row and column included.
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i)
      EXPECT_EQ(bilinear(g, {origin.x + i * spacing.x, origin.y + j * spacing.y}), g.at(i, j));
  // Outside, the value at the nearest point of the box.
  EXPECT_NEAR(bilinear(g, {-5.0, 2.5}), bilinear_function({-1.0, 2.5}), 1e-12);
  EXPECT_NEAR(bilinear(g, {1.3, 10.0}), bilinear_function({1.3, 3.0}), 1e-12);
  EXPECT_EQ(bilinear(g, {7.0, -7.0}), g.at(nx - 1, 0));
}

TEST(RegularGrid, TwoGridsInOneProgramKeepTheirOwnSamples) {
  Program program;
  program.params = {1.0, 2.0, 3.0};  // something before, as a primitive's parameters would be
  const std::vector<float> a{1, 2, 3, 4}, b{10, 20, 30, 40, 50, 60};
  const uint32_t first = append_grid(program, {0, 0}, {1, 1}, 2, 2, a.data());
  const uint32_t second = append_grid(program, {5, 5}, {2, 1}, 3, 2, b.data());
  EXPECT_EQ(first, 3u);
  EXPECT_EQ(second, 3u + kGridParams);
  ASSERT_EQ(program.samples.size(), 10u);

  const ProgramView view = program.view();
  const RegularGrid ga = grid_at(view.params, view.samples, first);
  const RegularGrid gb = grid_at(view.params, view.samples, second);
  EXPECT_EQ(bilinear(ga, {0.5, 0.5}), 2.5);
  EXPECT_EQ(bilinear(gb, {7.0, 5.5}), 35.0);
  EXPECT_EQ(gb.nx, 3u);
  EXPECT_EQ(gb.at(2, 1), 60.0f);
}

}  // namespace
}  // namespace meshd
