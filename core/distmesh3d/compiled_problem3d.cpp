#include "core/distmesh3d/compiled_problem3d.h"

#include "core/distmesh3d/geometry_domain3d.h"
#include "core/geometry3d/compile3d.h"

namespace meshd {

CompiledProblem3 compile_problem3(const Problem3& problem) {
  CompiledProblem3 out;
  out.geometry = std::make_shared<const Program3>(compile_geometry3(problem.geometry));
  out.range = size_range3(problem.size);
  out.uniform = problem.size.terms.empty();
  // The loop spaces its finest nodes h0 apart wherever h is smallest: rescale so that h0 means
  // the edge length where h is at its lowest bound, as in 2D.
  out.size = compile_size_field3(problem.size, out.range.low);
  out.request_h0 = problem.h0;
  out.h0 = problem.h0 * out.range.low;
  out.exact_band = kExactDistanceEdges * out.h0 * (out.range.high / out.range.low);
  out.auto_features = problem.auto_features;
  out.params = problem.params;
  return out;
}

}  // namespace meshd
