// What one DistMesh step measures, and the loop's two tests on it (step 3's retriangulation test
// and step 8's termination), shared by the loop (distmesh.cpp) and the GPU engine, which runs
// several steps per host round trip and must stop where the loop would look.
#pragma once

#include "core/common/hd.h"

namespace meshd {

// Every length is measured in the node's own size, h0 times the mean h of its bars: a node that
// moves a tenth of its edges does so in a fine region and in a coarse one alike. Measured in h0,
// the coarse regions of a graded field (edges up to h_max h0) retriangulated and kept the loop
// running several times as long as they needed to, for nothing a finer region could notice.
struct StepResult {
  double max_move = 0.0;   // largest move of an interior node (d < -geps) this step
  double max_drift = 0.0;  // largest |p - p_at_last_triangulation| after the step
  double rms_move = 0.0;   // root mean square of the interior moves
};

struct StepRule {
  double ttol = 0.0;             // retriangulate once some node drifted this far (params.h)
  double dptol = 0.0;            // the interior has settled when its rms move is under this
  double max_move_factor = 0.0;  // ... and no node moves more than this many dptol
  // A relaxation runs at least this long: right after a triangulation a lattice-like start can
  // be balanced everywhere inside while its boundary layer has not moved yet.
  int min_iterations = 0;

  // Step 3 of the next iteration: the points drifted far enough to retriangulate first.
  MESHD_HD bool needs_triangulation(double max_drift) const { return max_drift > ttol; }
  // Step 8: the relaxation is over after `iteration` (counted from 1): the interior has settled
  // as a whole and no node still moves far; waiting for the last annealing node to stop costs
  // hundreds of iterations and no quality.
  MESHD_HD bool converged(const StepResult& r, int iteration) const {
    return iteration >= min_iterations && r.rms_move < dptol &&
           r.max_move < max_move_factor * dptol;
  }
  // Where a run of several steps must hand back to the loop.
  MESHD_HD bool stops(const StepResult& r, int iteration) const {
    return needs_triangulation(r.max_drift) || converged(r, iteration);
  }
};

}  // namespace meshd
