// A validated job: its problem, compiled once when the request was converted (the worker meshes
// that compilation), and how the service runs it (request_conversion makes it).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/distmesh/compiled_problem.h"
#include "core/distmesh3d/compiled_problem3d.h"

namespace meshd {

// Which kind of worker runs a job. kAuto resolves to a GPU when the server has one.
enum class Backend { kAuto, kGpu, kCpu };

const char* backend_name(Backend backend);

struct JobOptions {
  Backend backend = Backend::kAuto;
  int priority = 0;            // [-10, 10]; higher runs first
  int snapshot_every = 0;      // iterations between snapshots; 0: none
  int snapshot_max_nodes = 0;  // no snapshots of a mesh with more nodes
  double timeout_s = 0;        // Submit jobs: limit from submission; 0: none
  std::string label;
};

struct JobSpec {
  CompiledProblem plane;                   // a plane job; unused when volume is set
  std::optional<CompiledProblem3> volume;  // a 3D job
  double estimated_nodes = 0;
  JobOptions options;
};

}  // namespace meshd
