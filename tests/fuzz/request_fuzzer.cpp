// libFuzzer target over the whole request path short of meshing at scale (request_pipeline.h):
// bytes -> MeshRequest (text format or binary) -> to_job_spec under tiny limits ->
// compile_problem -> generate_mesh on a one-thread CPU engine with a capped iteration count.
// scripts/fuzz.sh builds and runs it.
//
// Findings: a crash, a sanitizer report, a hang (libFuzzer's -timeout), or any exception other
// than meshd::Error, InvariantBroken included: it escapes, std::terminate prints it and aborts.
#include <google/protobuf/stubs/logging.h>

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/request_pipeline.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // protobuf logs every invalid UTF-8 string it parses; the server ignores those logs too.
  google::protobuf::SetLogHandler(nullptr);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  meshd::fuzz::run_request_input(data, size);
  return 0;
}
