// Launch wrappers of the 3D GPU engine's kernels (steps3d.cu), as launch.h has the 2D ones:
// plain host declarations over DeviceSpan views; each returns at once on empty input and checks
// its launch.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "core/common/vec3.h"
#include "core/distmesh/step_rule.cuh"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/size_field3_eval.cuh"
#include "kernels/device_span.cuh"

namespace meshd::gpu {

// A bar's two ends, lo < hi, as Topology3::bars holds them.
struct Bar3 {
  int32_t a, b;
};

// Partials of the L0 scale: sum of L^3 and of h^3 over the bars.
struct BarSums3 {
  double l3, h3;
};
// Partials of one step's measures.
struct StepSums3 {
  double max_move, max_drift, sum_sq, interior;
};

// Step 4: every bar's length and size at its midpoint (h = 1 unless `graded`), and the blocks'
// partial sums (partial: nonempty_reduce_blocks_for(bars.size) entries, launch.h).
void launch_measure_bars3(DeviceSpan<const Vec3> p, DeviceSpan<const Bar3> bars, SizeField3View fh,
                          bool graded, DeviceSpan<double> length, DeviceSpan<double> size,
                          DeviceSpan<BarSums3> partial, cudaStream_t stream);
// scale[0] = fscale cbrt(sum L^3 / sum h^3), distmeshnd's volume-matching L0 factor.
void launch_finish_scale3(DeviceSpan<const BarSums3> partial, double fscale, double* scale,
                          cudaStream_t stream);

struct MoveArgs3 {
  DeviceSpan<const Vec3> p;
  DeviceSpan<Vec3> p_next;
  DeviceSpan<Vec3> momentum;
  DeviceSpan<const Vec3> at_triangulation;
  DeviceSpan<const Bar3> bars;
  DeviceSpan<const int64_t> bar_offsets;  // #N + 1
  DeviceSpan<const int64_t> bar_ends;     // 2 b or 2 b + 1, as Topology3 documents
  DeviceSpan<const double> length, size;  // from measure_bars3
  const double* scale;                    // from finish_scale3
  Program3View fd;
  double band;  // the exact band of the distance (eval_sdf3's cap)
  int64_t fixed;
  double deltat, momentum_factor;
  double inside;  // -geps h0: a node deeper than this is interior
  double deps;    // the gradient's step, absolute
  double h0;
  DeviceSpan<StepSums3> partial;  // nonempty_reduce_blocks_for(p.size) entries
};
// Steps 5, 7 and 8 per node (step3d.h): the gathered bar forces, the move, the projection, the
// measures' partials.
void launch_move_nodes3(const MoveArgs3& args, cudaStream_t stream);
// The step's measures from the partials.
void launch_finish_step3(DeviceSpan<const StepSums3> partial, StepResult* result,
                         cudaStream_t stream);

// Step 6: flags[i] = 1 for each non-fixed end i of a bar with scale h > 2 L (flags zeroed
// first by the caller).
void launch_mark_crowded3(DeviceSpan<const Bar3> bars, DeviceSpan<const double> length,
                          DeviceSpan<const double> size, const double* scale, int64_t fixed,
                          DeviceSpan<uint8_t> flags, cudaStream_t stream);

}  // namespace meshd::gpu
