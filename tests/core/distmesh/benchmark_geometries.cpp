#include "tests/core/distmesh/benchmark_geometries.h"

#include <cmath>
#include <stdexcept>

namespace meshd::testing {
namespace {

Shape named(Shape s, std::string name) {
  s.name = std::move(name);
  return s;
}

Shape square_with_hole() {
  Shape square{Rectangle{{-1, -1}, {1, 1}}, "outer", ""};
  Shape hole{Circle{{0, 0}, 0.5}, "hole", ""};
  return Shape{Csg{CsgOp::kDifference, {square, hole}}, "", ""};
}

const std::vector<Vec2> kG3Vertices = {{-0.4, -0.5}, {0.4, -0.2}, {0.4, -0.7}, {1.5, -0.4},
                                       {0.9, 0.1},   {1.6, 0.8},  {0.5, 0.5},  {0.2, 1},
                                       {0.1, 0.4},   {-0.7, 0.7}};

}  // namespace

Problem benchmark_problem(const std::string& id, double h0) {
  Problem p;
  p.h0 = h0;
  if (id == "G1") {
    p.geometry = named(Shape{Circle{{0, 0}, 1}, "", ""}, "outer");
  } else if (id == "G2") {
    p.geometry = square_with_hole();
  } else if (id == "G3") {
    p.geometry = named(Shape{Polygon{kG3Vertices}, "", ""}, "outer");
  } else if (id == "G4") {
    p.geometry = named(Shape{Ellipse{{0, 0}, 2, 1}, "", ""}, "outer");
  } else if (id == "G5") {
    p.geometry = square_with_hole();
    DistanceSize graded;
    graded.shape = Shape{Circle{{0, 0}, 0.5}, "", ""};
    graded.h_min = 1.0;
    graded.slope = 4.0;
    graded.h_max = 2.0;
    p.size.terms.push_back(graded);
  } else {
    throw std::invalid_argument("unknown benchmark geometry " + id);
  }
  return p;
}

double benchmark_area(const std::string& id) {
  if (id == "G1") return M_PI;
  if (id == "G2" || id == "G5") return 4.0 - M_PI * 0.25;
  if (id == "G4") return 2.0 * M_PI;
  if (id == "G3") {
    double a = 0.0;
    for (size_t i = 0, j = kG3Vertices.size() - 1; i < kG3Vertices.size(); j = i++)
      a += cross(kG3Vertices[j], kG3Vertices[i]);
    return std::fabs(0.5 * a);
  }
  throw std::invalid_argument("unknown benchmark geometry " + id);
}

}  // namespace meshd::testing
