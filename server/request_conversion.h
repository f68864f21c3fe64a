// The one validation and conversion layer between the API (meshd.v1.MeshRequest) and core's
// Problem. Every entry point (server, CLI, benchmarks) goes through to_problem, so that a request
// means the same thing and fails the same way wherever it comes from.
//
// Errors: every bad field throws Error(kInvalidArgument) with the protobuf field path
// ("geometry.difference.subtract[1].circle.radius", "params.deltat", "fixed_points[2].x") and a
// message that states the allowed range and the value received. A valid request that is larger
// than `limits` allow (too many estimated nodes) throws Error(kResourceExhausted) naming "h0".
#pragma once

#include <cstdint>
#include <string>

#include "core/distmesh/problem.h"
#include "meshd/v1/request.pb.h"
#include "server/job_spec.h"

namespace meshd {

class ThreadPool;

// What one request may ask for. The defaults are the ones quoted in the proto comments; a
// server may lower or raise them (a deployment with small GPUs lowers max_nodes).
struct ConversionLimits {
  int64_t max_nodes = 5'000'000;   // estimated node count (RESOURCE_EXHAUSTED above)
  int max_tree_depth = 32;         // levels of one Shape tree; a lone primitive is 1
  int max_tree_nodes = 1'000'000;  // Shape nodes in one tree (geometry or a size term)
  // Shape3 nodes in one 3D tree: every point evaluates all of them (no spatial index in 3D yet).
  int max_tree3_nodes = 1'000;
  int64_t max_polyhedron_triangles = 2'000'000;  // triangles of all the polyhedra of a request
  int max_polygon_vertices = 5'000'000;          // vertices of one polygon (indexed: bvh.h)
  double max_size_ratio = 1000;  // bound on (largest h) / (smallest h) of the size field
  int max_size_terms = 100;      // terms of the size field
  int64_t max_size_grid_values = 16'777'216;  // samples of all grid terms together
  int max_fixed_points = 100'000;             // entries of fixed_points
  // Largest mesh whose snapshots may stream: one snapshot of 50k nodes is about 1.7 MB, well
  // inside a client's default 4 MiB message limit. A volume's limit is volume_snapshot_nodes.
  int max_snapshot_nodes = 50'000;
  // Samples of all the distance grids in one tree (geometry or a size term), 4 bytes each;
  // RESOURCE_EXHAUSTED above it. The default is a 4096 x 4096 image.
  int64_t max_grid_samples = 16'777'216;
};

// The largest volume whose snapshots may stream: a node of a tetrahedral snapshot carries about
// 2.5 times the bytes of a plane one (three coordinates and some 5.5 tetrahedra against two and
// 2 triangles), so that the same message size allows 2/5 of max_snapshot_nodes (20,000 by
// default).
inline int volume_snapshot_nodes(const ConversionLimits& limits) {
  return limits.max_snapshot_nodes / 5 * 2;
}

// Validates `request` against the proto's documented ranges and `limits`, and converts it.
// Lengths keep the request's unit; angles become radians; unset optional parameters take core's
// defaults (Params); names propagate down the tree (a node's `name` is its own or its nearest
// named ancestor's, empty when neither; the geometry compiler names the rest). Estimates the
// node count last, so a Problem that comes back will mesh to between 3 and max_nodes nodes.
//
//   request  the API message, as received or parsed from text
//   limits   the caller's limits
Problem to_problem(const v1::MeshRequest& request, const ConversionLimits& limits = {});

// One plane shape tree at `path` (its errors name fields below it), as to_problem converts the
// geometry: a 3D extrusion's or revolution's profile.
Shape to_shape(const v1::Shape& shape, const ConversionLimits& limits, const std::string& path);

// to_problem (to_problem3, volume_conversion.h, for a request with a volume), then the
// service's options (options.*) with their ranges. Snapshots of a request
// estimated above the snapshot limit are RESOURCE_EXHAUSTED naming "options.snapshot_every".
// The node estimate's samples, and a gradation's, run over `pool`'s threads when one is given.
JobSpec to_job_spec(const v1::MeshRequest& request, const ConversionLimits& limits = {},
                    ThreadPool* pool = nullptr);

}  // namespace meshd
