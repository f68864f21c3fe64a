// The spatial indexes of compiled programs (bvh.h): a tree's shape, and evaluation through an
// indexed polygon or union against the plain walk over every edge or operand, which they must
// reproduce bit for bit (the sign of a point lying on a polygon's edge excepted, where the
// distance is 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/geometry/bounds.h"
#include "core/geometry/bvh.h"
#include "core/geometry/compile.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

using testing::circle;
using testing::csg;
using testing::rectangle;

constexpr double kPi = std::numbers::pi;

Shape polygon(std::vector<Vec2> v) { return Shape{Polygon{std::move(v)}, "", ""}; }

// A star-shaped ring of n vertices whose radius wanders between 0.5 and 1.5: long, ragged,
// with many edges crossing every horizontal line through it.
std::vector<Vec2> ragged_ring(int n, Vec2 c, double scale, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> wobble(0.5, 1.5);
  std::vector<Vec2> v;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n, r = scale * wobble(rng);
    v.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return v;
}

// A comb of axis-aligned teeth on integer coordinates: query points on the same lines as its
// vertices and edges hit every tie of the crossing rule.
std::vector<Vec2> comb(int teeth) {
  std::vector<Vec2> v{{0, 0}, {2.0 * teeth, 0}};
  for (int t = teeth - 1; t >= 0; --t) {
    v.push_back({2.0 * t + 2, 3});
    v.push_back({2.0 * t + 1, 3});
    v.push_back({2.0 * t + 1, 1});
    v.push_back({2.0 * t + 0, 1});
  }
  v.pop_back();  // the last tooth's inner corner would repeat (0, 1)... keep the ring simple
  v.push_back({0, 3});
  return v;
}

std::vector<Vec2> queries(Box b, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double wx = b.max.x - b.min.x, wy = b.max.y - b.min.y;
  std::uniform_real_distribution<double> x(b.min.x - 0.3 * wx, b.max.x + 0.3 * wx);
  std::uniform_real_distribution<double> y(b.min.y - 0.3 * wy, b.max.y + 0.3 * wy);
  std::vector<Vec2> q;
  for (int i = 0; i < n; ++i) q.push_back({x(rng), y(rng)});
  return q;
}

// The indexed polygon of `program` (its only instruction) against the plain edge walk.
void expect_polygon_index_agrees(const Program& program, const std::vector<Vec2>& points) {
  ASSERT_EQ(program.code.size(), 1u);
  const Instruction ins = program.code[0];
  ASSERT_NE(ins.bvh, kNoBvh) << "a polygon this long should be indexed";
  const double* q = program.params.data() + ins.operand;
  int sign_flips = 0;
  for (Vec2 p : points) {
    const double indexed = eval_sdf(program.view(), p), plain = sdf_polygon(q, p);
    ASSERT_EQ(std::fabs(indexed), std::fabs(plain)) << p.x << " " << p.y;
    if (plain != 0.0) sign_flips += (indexed < 0) != (plain < 0);
  }
  EXPECT_EQ(sign_flips, 0);
}

TEST(BvhBuild, LeavesCoverEveryItemOnceAndBoxesNest) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<BvhItem> items;
  for (uint32_t i = 0; i < 1000; ++i) {
    const Vec2 a{u(rng), u(rng)};
    items.push_back({{a, {a.x + 1, a.y + 2}}, 3 * i, 3 * i + 3});
  }
  std::vector<BvhNode> nodes(5);  // a tree appended after other trees' nodes
  const uint32_t root = build_bvh(items, nodes);
  EXPECT_EQ(root, 5u);
  std::vector<int> seen(1000, 0);
  int deepest = 0;
  std::vector<std::pair<uint32_t, int>> stack{{root, 1}};
  while (!stack.empty()) {
    const auto [at, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    const BvhNode& n = nodes[at];
    if (n.leaf) {
      ASSERT_EQ(n.last, n.first + 3);
      ++seen[n.first / 3];
      continue;
    }
    for (uint32_t child : {n.first, n.last}) {
      const Box& c = nodes[child].box;
      EXPECT_TRUE(c.min.x >= n.box.min.x && c.min.y >= n.box.min.y && c.max.x <= n.box.max.x &&
                  c.max.y <= n.box.max.y);
      stack.push_back({child, depth + 1});
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 1000);
  EXPECT_LE(deepest, 11);  // ceil(log2 1000) + 1
  EXPECT_LE(deepest, kMaxBvhDepth);
}

TEST(IndexedPolygon, RaggedRingMatchesThePlainWalk) {
  const Program program = compile_geometry(polygon(ragged_ring(5000, {3, -1}, 2.0, 11)));
  expect_polygon_index_agrees(program, queries(program_bounds(program), 20000, 12));
}

TEST(IndexedPolygon, CombOnGridLinesMatchesThePlainWalk) {
  const Program program = compile_geometry(polygon(comb(40)));
  std::vector<Vec2> points = queries(program_bounds(program), 5000, 13);
  for (int x = -2; x <= 84; ++x)
    for (int y = -1; y <= 4; ++y) {
      points.push_back({0.5 * x, 1.0 * y});
      points.push_back({0.5 * x + 0.25, 0.5 * y});
    }
  expect_polygon_index_agrees(program, points);
}

TEST(IndexedPolygon, ShortPolygonStaysPlain) {
  const Program program = compile_geometry(polygon(ragged_ring(20, {0, 0}, 1.0, 3)));
  EXPECT_EQ(program.code[0].bvh, kNoBvh);
  EXPECT_TRUE(program.nodes.empty());
}

// Many small shapes of every kind, some overlapping, with one unbounded operand.
std::vector<Shape> scattered_shapes(int n, uint64_t seed, bool with_half_plane) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 10), r(0.05, 0.4);
  std::vector<Shape> out;
  for (int i = 0; i < n; ++i) {
    const Vec2 c{u(rng), u(rng)};
    const double s = r(rng);
    switch (i % 4) {
      case 0:
        out.push_back(circle(c, s));
        break;
      case 1:
        out.push_back(rectangle(c, {c.x + s, c.y + 0.5 * s}));
        break;
      case 2:
        out.push_back(Shape{Ellipse{c, s, 0.4 * s}, "", ""});
        break;
      default:
        out.push_back(polygon(ragged_ring(i % 8 == 3 ? 6 : 80, c, 0.5 * s, seed + i)));
    }
  }
  if (with_half_plane) out.push_back(Shape{HalfPlane{{1, 1}, -3}, "", ""});
  return out;
}

// The whole program with its indexes against the same program evaluated with none followed
// (eval_program<0> runs every fold): same value bit for bit, same owner.
void expect_union_index_agrees(const Shape& shape, int expected_unions, uint64_t seed) {
  const Program program = compile_geometry(shape);
  const auto unions = std::count_if(program.code.begin(), program.code.end(),
                                    [](auto& ins) { return ins.op == Op::kUnionIndexed; });
  ASSERT_EQ(unions, expected_unions);
  const auto end = static_cast<uint32_t>(program.code.size());
  for (Vec2 p : queries({{0, 0}, {10, 10}}, 20000, seed)) {
    int who_indexed = -2, who_plain = -2;
    const double indexed = eval_sdf_range(program.view(), 0, end, p, &who_indexed);
    const double plain = eval_program<0>(program.view(), 0, end, p, &who_plain);
    ASSERT_EQ(indexed, plain) << p.x << " " << p.y;
    ASSERT_EQ(who_indexed, who_plain) << p.x << " " << p.y;
  }
}

TEST(IndexedUnion, UnionOfManyShapesMatchesTheFold) {
  expect_union_index_agrees(csg(CsgOp::kUnion, scattered_shapes(400, 21, false)), 1, 22);
}

TEST(IndexedUnion, UnboundedOperandIsAlwaysVisited) {
  expect_union_index_agrees(csg(CsgOp::kUnion, scattered_shapes(100, 23, true)), 1, 24);
}

TEST(IndexedUnion, DifferenceOfManyHolesMatchesTheFold) {
  std::vector<Shape> ops{rectangle({0, 0}, {10, 10})};
  for (Shape& s : scattered_shapes(300, 25, false)) ops.push_back(std::move(s));
  expect_union_index_agrees(csg(CsgOp::kDifference, ops), 1, 26);
}

TEST(IndexedUnion, IslandsWithLakesNestTwoLevels) {
  // A union of islands, each a disk minus many lakes: the outer index, and one per island,
  // whose fold runs below the level the evaluator follows.
  std::vector<Shape> islands;
  for (int i = 0; i < 9; ++i) {
    const Vec2 c{1.7 + 3.3 * (i % 3), 1.7 + 3.3 * (i / 3)};
    std::vector<Shape> ops{circle(c, 1.6)};
    for (int k = 0; k < 12; ++k) {
      const double a = 2 * kPi * k / 12;
      ops.push_back(circle({c.x + std::cos(a), c.y + std::sin(a)}, 0.2));
    }
    islands.push_back(csg(CsgOp::kDifference, ops));
  }
  expect_union_index_agrees(csg(CsgOp::kUnion, islands), 10, 27);
}

TEST(IndexedUnion, BoundsAreThoseOfThePlainTree) {
  const Shape shape = csg(CsgOp::kUnion, scattered_shapes(50, 28, false));
  const Program program = compile_geometry(shape);
  Box plain{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
  for (const Shape& s : std::get<Csg>(shape.node).operands) {
    const Box b = program_bounds(compile_geometry(s));
    plain = {{std::min(plain.min.x, b.min.x), std::min(plain.min.y, b.min.y)},
             {std::max(plain.max.x, b.max.x), std::max(plain.max.y, b.max.y)}};
  }
  const Box b = program_bounds(program);
  EXPECT_EQ(b.min.x, plain.min.x);
  EXPECT_EQ(b.min.y, plain.min.y);
  EXPECT_EQ(b.max.x, plain.max.x);
  EXPECT_EQ(b.max.y, plain.max.y);
}

}  // namespace
}  // namespace meshd
