// What the request fuzzer does with one input (request_fuzzer.cpp), shared with the regression
// test that replays tests/fuzz/corpus/ in the normal build (server/fuzz_regression_test.cpp).
//
// Input: the first byte chooses the format (even: text format, as meshctl reads it; odd: binary
// wire format, as the server receives it); the rest is the MeshRequest.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "server/request_conversion.h"

namespace meshd::fuzz {

// Small enough that one input meshes in well under a second under ASan and coverage
// instrumentation, large enough that every limit is reachable by a short input.
ConversionLimits fuzz_limits();

// A result that breaks a promise of generate_mesh (see run_request_input).
class InvariantBroken : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// Runs one input through the whole request path short of meshing at scale: parse, to_job_spec
// under fuzz_limits(), compile_problem, generate_mesh on a one-thread CPU engine with at most 50
// iterations (a request estimated above 300 nodes is meshed at the h0 that aims it at 300, which
// to_job_spec accepts too; fscale is capped at 1.25, and a mesh that the clean-up emptied is not
// reported, while their open findings stand). Returns
// normally when the request was meshed, or refused with a meshd::Error (any code: the expected
// outcome of a bad request), or is not a parsable binary message. Throws InvariantBroken when the
// result breaks a promise, converged or not: the mesh fails check_validity, or has no triangle
// though estimated at 30 nodes or more, or the loop ran past max_iterations, or stopped short of
// it without converging. A volume (3D) request is meshed at about the same node count with
// generate_mesh3d and held to the same promises, check_tet_validity in place of check_validity.
// Anything else (another exception, a crash, a sanitizer report) is a
// finding.
void run_request_input(const uint8_t* data, size_t size);

}  // namespace meshd::fuzz
