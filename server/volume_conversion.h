// The 3D half of the conversion layer (request_conversion.h): a MeshRequest with a `volume`
// becomes core's Problem3, every bad field named by its path and allowed range, as in 2D.
#pragma once

#include "core/distmesh3d/compiled_problem3d.h"
#include "core/distmesh3d/problem3d.h"
#include "meshd/v1/request.pb.h"
#include "server/request_conversion.h"

namespace meshd {

// Validates the volume request (request.volume set) against the proto's ranges and `limits`,
// and converts it; sets `estimated_nodes` to the node count it checked against
// limits.max_nodes (RESOURCE_EXHAUSTED naming "h0" above it, INVALID_ARGUMENT below 4).
Problem3 to_problem3(const v1::MeshRequest& request, const ConversionLimits& limits,
                     double& estimated_nodes);

// The same, compiled (compile_problem3): the compilation the node count was checked on, which a
// job keeps for its worker.
CompiledProblem3 to_compiled_problem3(const v1::MeshRequest& request,
                                      const ConversionLimits& limits, double& estimated_nodes);

}  // namespace meshd
