// estimate_node_count and h0_for_node_count against the formula of geometries.md,
// N = (2 / sqrt(3)) * integral of 1 / (h0 h(p))^2 dA.
#include "core/distmesh/node_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

constexpr double kTwoOverSqrt3 = 1.1547005383792515;

// integral of r / h(r)^2 dr over [r0, r1] for G5's h(r) = min(4r - 1, 2), by composite Simpson
// on each smooth piece (the kink is at r = 0.75).
double g5_radial(double r0, double r1) {
  auto simpson = [](auto f, double a, double b) {
    if (b <= a) return 0.0;
    constexpr int kN = 200;  // even
    const double h = (b - a) / kN;
    double s = f(a) + f(b);
    for (int i = 1; i < kN; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
    return s * h / 3;
  };
  auto f = [](double r) {
    const double h = std::min(4 * r - 1, 2.0);
    return r / (h * h);
  };
  const double kink = 0.75;
  return simpson(f, r0, std::min(r1, kink)) + simpson(f, std::max(r0, kink), r1);
}

// integral of 1 / h^2 over G5's domain, [-1,1]^2 minus the disk r < 0.5: eight times the
// wedge 0 <= theta <= pi/4, where r runs from 0.5 to 1 / cos(theta).
double g5_integral() {
  constexpr int kN = 400;  // even
  const double a = 0, b = M_PI / 4, h = (b - a) / kN;
  auto wedge = [](double t) { return g5_radial(0.5, 1 / std::cos(t)); };
  double s = wedge(a) + wedge(b);
  for (int i = 1; i < kN; ++i) s += (i % 2 ? 4 : 2) * wedge(a + i * h);
  return 8 * s * h / 3;
}

TEST(NodeEstimate, G5QuadratureAgreesWithTheClosedForm) {
  // The ring 0.5 < r < 0.75 lies inside the square: 2 pi (ln 2 + 1/2) / 16; beyond it h = 2:
  // (4 - pi 0.75^2) / 4.
  const double closed = M_PI * (std::log(2.0) + 0.5) / 8 + (4 - M_PI * 0.5625) / 4;
  EXPECT_NEAR(g5_integral(), closed, 1e-9);
}

TEST(NodeEstimate, UniformGeometriesMatchTheAreaFormula) {
  for (const std::string id : {"G1", "G2", "G3", "G4"}) {
    for (double h0 : {0.05, 0.013}) {
      const double want = kTwoOverSqrt3 * testing::benchmark_area(id) / (h0 * h0);
      const double got = estimate_node_count(testing::benchmark_problem(id, h0));
      EXPECT_NEAR(got / want, 1.0, 0.02) << id << " h0 " << h0 << ": " << got << " vs " << want;
    }
  }
}

TEST(NodeEstimate, GradedG5MatchesTheIntegral) {
  const double integral = g5_integral();
  for (double h0 : {0.05, 0.01}) {
    const double want = kTwoOverSqrt3 * integral / (h0 * h0);
    const double got = estimate_node_count(testing::benchmark_problem("G5", h0));
    EXPECT_NEAR(got / want, 1.0, 0.02) << "h0 " << h0 << ": " << got << " vs " << want;
    // Grading matters: far fewer nodes than the uniform G2 at the same h0.
    EXPECT_LT(got, 0.5 * estimate_node_count(testing::benchmark_problem("G2", h0)));
  }
}

TEST(NodeEstimate, ScalesAsOneOverH0Squared) {
  const Problem p = testing::benchmark_problem("G3", 0.1);
  Problem q = p;
  q.h0 = 0.025;
  EXPECT_NEAR(estimate_node_count(q) / estimate_node_count(p), 16.0, 1e-9);
}

TEST(NodeEstimate, H0ForNodeCountHitsTheTarget) {
  for (const std::string id : {"G1", "G2", "G3", "G4", "G5"}) {
    Problem p = testing::benchmark_problem(id, 0.1);
    for (double nodes : {2000.0, 1e6}) {
      p.h0 = h0_for_node_count(p, nodes);
      EXPECT_GT(p.h0, 0.0);
      EXPECT_NEAR(estimate_node_count(p) / nodes, 1.0, 1e-9) << id << " " << nodes;
    }
  }
  // G1 at h0 = 0.01 is about 36,000 nodes (geometries.md).
  EXPECT_NEAR(estimate_node_count(testing::benchmark_problem("G1", 0.01)), 36276, 400);
}

TEST(NodeEstimate, EmptyDomainIsAnError) {
  Problem p;
  p.h0 = 0.1;
  p.geometry = Shape{Csg{CsgOp::kIntersection,
                         {Shape{Circle{{0, 0}, 1}, "", ""}, Shape{Circle{{5, 0}, 1}, "", ""}}},
                     "", ""};
  try {
    estimate_node_count(p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "geometry");
  }
}

// The survey's samples run over threads and add up in one order: the same bits on any number
// of threads, graded (G5) or not (G3's polygon).
TEST(NodeEstimate, ASurveyOverThreadsGivesTheSameBitsAsOneThread) {
  for (const std::string id : {"G3", "G5"}) {
    for (double h0 : {0.1, 0.003}) {
      const CompiledProblem c = compile_problem(testing::benchmark_problem(id, h0));
      const DomainSurvey alone = survey_domain(c);
      for (unsigned threads : {2u, 3u, 8u}) {
        ThreadPool pool(threads);
        const DomainSurvey shared = survey_domain(c, &pool);
        EXPECT_EQ(shared.nodes, alone.nodes) << id << " " << h0 << " " << threads;
        EXPECT_EQ(shared.depth, alone.depth) << id << " " << h0 << " " << threads;
        EXPECT_EQ(shared.inverse_size, alone.inverse_size) << id << " " << h0 << " " << threads;
      }
    }
  }
}

// A surveyed problem keeps its integral, which holds for any h0: the estimate reads it instead
// of sampling the domain again.
TEST(NodeEstimate, ASurveyedProblemCountsItsNodesFromItsIntegral) {
  CompiledProblem c = compile_problem(testing::benchmark_problem("G5", 0.05));
  const DomainSurvey survey = survey_domain(c);
  EXPECT_EQ(estimate_node_count(c), survey.nodes);
  c.inverse_size_integral = survey.inverse_size;
  EXPECT_EQ(estimate_node_count(c), survey.nodes);
  c.h0 *= 2;
  EXPECT_EQ(estimate_node_count(c), survey.nodes / 4);
  c.inverse_size_integral = 3 * survey.inverse_size;  // not sampled again: the count follows it
  EXPECT_NEAR(estimate_node_count(c), 0.75 * survey.nodes, 1e-12 * survey.nodes);
}

}  // namespace
}  // namespace meshd
