// Every primitive's distance against brute force: under a random similarity, |sdf(p)| equals the
// smallest distance from p to a dense sample of the surface (never more, and less by at most the
// sampling's gap), and its sign says whether p lies in the solid (tested in the primitive's own
// frame, through the inverse transform).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kSteps = 160;  // samples per parameter of each surface patch

// Surface samples in the primitive's own frame, and how far any surface point can lie from the
// nearest of them.
struct Surface {
  std::vector<Vec3> samples;
  double gap = 0.0;

  // The surface of revolution swept by the profile segment (r0, z0) -> (r1, z1) about z.
  void revolve(double r0, double z0, double r1, double z1) {
    const double rmax = std::max(r0, r1), len = std::hypot(r1 - r0, z1 - z0);
    for (int i = 0; i <= kSteps; ++i) {
      const double t = double(i) / kSteps, r = r0 + t * (r1 - r0), z = z0 + t * (z1 - z0);
      for (int j = 0; j < kSteps; ++j) {
        const double phi = 2 * kPi * j / kSteps;
        samples.push_back({r * std::cos(phi), r * std::sin(phi), z});
      }
    }
    gap = std::max(gap, 0.5 * std::hypot(len / kSteps, 2 * kPi * rmax / kSteps));
  }
};

struct Case {
  std::string what;
  Shape3 shape;                      // in its own frame
  Surface surface;                   // in its own frame
  std::function<bool(Vec3)> inside;  // in its own frame
  double extent = 0.0;               // the solid lies within [-extent, extent]^3 of its frame
};

std::vector<Case> cases() {
  std::vector<Case> out;
  {
    Case c{"sphere", testing::sphere({0, 0, 0}, 1), {}, [](Vec3 p) { return norm(p) <= 1; }, 1};
    for (int i = 0; i <= kSteps; ++i) {  // a stack of circles from pole to pole
      const double th = kPi * i / kSteps;
      for (int j = 0; j < kSteps; ++j) {
        const double phi = 2 * kPi * j / kSteps;
        c.surface.samples.push_back(
            {std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th)});
      }
    }
    c.surface.gap = 0.5 * std::hypot(kPi / kSteps, 2 * kPi / kSteps);
    out.push_back(std::move(c));
  }
  {
    const Vec3 lo{-1, -0.5, -0.25}, hi{1, 0.5, 0.75};
    Case c{"cuboid",
           testing::cuboid(lo, hi),
           {},
           [=](Vec3 p) {
             return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
                    p.z <= hi.z;
           },
           1};
    const double lo3[3] = {lo.x, lo.y, lo.z}, hi3[3] = {hi.x, hi.y, hi.z};
    for (int axis = 0; axis < 3; ++axis) {  // each pair of faces as a grid
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (double side : {lo3[axis], hi3[axis]})
        for (int i = 0; i <= kSteps; ++i)
          for (int j = 0; j <= kSteps; ++j) {
            double v[3];
            v[axis] = side;
            v[a] = lo3[a] + (hi3[a] - lo3[a]) * i / kSteps;
            v[b] = lo3[b] + (hi3[b] - lo3[b]) * j / kSteps;
            c.surface.samples.push_back({v[0], v[1], v[2]});
          }
    }
    c.surface.gap = 0.5 * std::hypot(2.0 / kSteps, 1.0 / kSteps);
    out.push_back(std::move(c));
  }
  // Solids of revolution about z, from their profile's segments in the (r, z) half-plane.
  auto frustum_case = [](std::string what, Shape3 shape, double rb, double rt, double h) {
    Case c{std::move(what),
           std::move(shape),
           {},
           [=](Vec3 p) {
             const double r = std::hypot(p.x, p.y);
             return p.z >= 0 && p.z <= h && r <= rb + (rt - rb) * p.z / h;
           },
           std::max({rb, rt, h})};
    c.surface.revolve(0, 0, rb, 0);
    c.surface.revolve(rb, 0, rt, h);
    c.surface.revolve(rt, h, 0, h);
    return c;
  };
  out.push_back(frustum_case("cylinder", testing::cylinder({0, 0, 0}, 0.8, 1.5), 0.8, 0.8, 1.5));
  out.push_back(frustum_case("cone", testing::frustum({0, 0, 0}, 1, 0, 1.2), 1, 0, 1.2));
  out.push_back(frustum_case("frustum", testing::frustum({0, 0, 0}, 1, 0.4, 0.7), 1, 0.4, 0.7));
  out.push_back(
      frustum_case("inverted frustum", testing::frustum({0, 0, 0}, 0.3, 1.2, 1), 0.3, 1.2, 1));
  out.push_back(
      frustum_case("inverted cone", testing::frustum({0, 0, 0}, 0, 0.9, 0.6), 0, 0.9, 0.6));
  {
    const double big = 1, small = 0.35;
    Case c{"torus",
           testing::torus({0, 0, 0}, big, small),
           {},
           [=](Vec3 p) {
             const double r = std::hypot(p.x, p.y) - big;
             return r * r + p.z * p.z <= small * small;
           },
           big + small};
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; j < kSteps; ++j) {
        const double u = 2 * kPi * i / kSteps, v = 2 * kPi * j / kSteps;
        const double r = big + small * std::cos(v);
        c.surface.samples.push_back({r * std::cos(u), r * std::sin(u), small * std::sin(v)});
      }
    c.surface.gap = 0.5 * std::hypot(2 * kPi * (big + small) / kSteps, 2 * kPi * small / kSteps);
    out.push_back(std::move(c));
  }
  return out;
}

TEST(Sdf3Property, EveryPrimitiveMatchesBruteForceUnderARandomSimilarity) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::normal_distribution<double> jitter(0, 0.05);
  for (Case& c : cases()) {
    const Similarity3 t{std::exp(unit(rng)),
                        {unit(rng), unit(rng), unit(rng)},
                        3 * unit(rng),
                        {5 * unit(rng), 5 * unit(rng), 5 * unit(rng)}};
    const Similarity3 back{1, t.axis, -t.angle, {}};  // R^-1
    const Program3 program = compile_geometry3(testing::transformed3(c.shape, t));
    std::vector<Vec3> world;
    for (Vec3 s : c.surface.samples) world.push_back(apply(t, s));
    const double gap = t.scale * c.surface.gap;

    // Points in the box around the solid, points just off its surface, and points on its axis
    // (the solids of revolution's hardest case), all in the primitive's own frame.
    std::vector<Vec3> local;
    for (int i = 0; i < 150; ++i)
      local.push_back(1.6 * c.extent * Vec3{unit(rng), unit(rng), unit(rng)});
    std::uniform_int_distribution<size_t> pick(0, c.surface.samples.size() - 1);
    for (int i = 0; i < 150; ++i)
      local.push_back(c.surface.samples[pick(rng)] + Vec3{jitter(rng), jitter(rng), jitter(rng)});
    for (int i = 0; i < 30; ++i) local.push_back({1e-9 * unit(rng), 0, 1.6 * c.extent * unit(rng)});

    for (Vec3 l : local) {
      const Vec3 p = apply(t, l);
      const double d = eval_sdf3(program.view(), p);
      double brute = INFINITY;
      for (Vec3 s : world) brute = std::min(brute, norm(p - s));
      SCOPED_TRACE(c.what + " at local (" + std::to_string(l.x) + ", " + std::to_string(l.y) +
                   ", " + std::to_string(l.z) + ")");
      EXPECT_LE(std::fabs(d), brute + 1e-12);  // the samples lie on the surface
      EXPECT_GE(std::fabs(d), brute - gap);
      // The inverse transform back into the primitive's frame, where membership is plain.
      const Vec3 back_local = (1.0 / t.scale) * rotate(back, p - t.offset);
      if (c.inside(back_local)) {
        EXPECT_LE(d, 1e-12);
      } else {
        EXPECT_GE(d, -1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace meshd
