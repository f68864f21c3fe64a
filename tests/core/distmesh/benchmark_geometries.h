// G1-G5 of geometries.md built directly as core Problems, so that core tests need no protobuf.
#pragma once

#include <string>

#include "core/distmesh/problem.h"

namespace meshd::testing {

// id: "G1".."G5"; h0 absolute. Square corners and polygon vertices come from auto_corners.
Problem benchmark_problem(const std::string& id, double h0);
// Exact domain area.
double benchmark_area(const std::string& id);

}  // namespace meshd::testing
