// What one DistMesh step measures, and the loop's two tests on it (step 3's retriangulation test
// and step 8's termination), shared by the loop (distmesh.cpp) and the GPU engine, which runs
// several steps per host round trip and must stop where the loop would look.
#pragma once

#include <cmath>

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

// How the farthest interior move has fared over the settled steps (rms under dptol) of a
// relaxation so far (StepRule::patience), and the rms move over all its steps
// (StepRule::rms_patience).
struct Settling {
  double lowest_max = INFINITY;  // the smallest max_move of a settled step
  int stalled = 0;               // settled steps since lowest_max last fell
  double rms_record = INFINITY;  // the rms_move of the last step that made progress
  int rms_stalled = 0;           // steps since then
};

struct StepRule {
  double ttol = 0.0;             // retriangulate once some node drifted this far (params.h)
  double dptol = 0.0;            // the interior has settled when its rms move is under this
  double max_move_factor = 0.0;  // ... and no node moves more than this many dptol
  // A relaxation runs at least this long: right after a triangulation a lattice-like start can
  // be balanced everywhere inside while its boundary layer has not moved yet.
  int min_iterations = 0;
  // ... and once the interior has settled (rms under dptol), the farthest move must keep
  // falling: after this many settled steps without a new low it is cycling, not settling, and
  // the relaxation ends at that step (0: never). A node can cycle for ever: an edge flips at a
  // retriangulation, the forces turn, the node walks back, the edge flips back (in a
  // coastline's narrow channels a few nodes repeated the same moves every 200 iterations until
  // max_iterations). Their neighbourhood is left to the clean-up. A boundary layer that is still
  // annealing sets new lows all the time and is waited for.
  int patience = 0;
  // A coarser level of a multilevel run only prepares the next level's start, and may end
  // unsettled: after this many steps in which the rms move never fell under rms_progress times
  // its last record, it is oscillating more than relaxing, and it ends there (0: never). Where
  // channels are narrower than such a level's edges, a few hundred nodes moved a tenth of their
  // edge at every step, the whole level retriangulated at every step, and its rms move fell by a
  // tenth per hundred steps (a level that settles loses most of it in a hundred).
  int rms_patience = 0;
  double rms_progress = 1.0;
  // The record before the first step the engine is asked for: the loop's, which the engine
  // carries on through a batch (settle).
  Settling settling;

  // Step 3 of the next iteration: the points drifted far enough to retriangulate first.
  MESHD_HD bool needs_triangulation(double max_drift) const { return max_drift > ttol; }
  // The record `s` after a step with result r.
  MESHD_HD Settling settle(Settling s, const StepResult& r) const {
    track(r.rms_move, rms_progress, s.rms_record, s.rms_stalled);
    if (r.rms_move < dptol) track(r.max_move, 1.0, s.lowest_max, s.stalled);
    return s;
  }
  // A value under `progress` times its record is the new record; any other adds a stalled step.
  MESHD_HD static void track(double value, double progress, double& record, int& stalled) {
    if (value < progress * record) {
      record = value;
      stalled = 0;
    } else {
      ++stalled;
    }
  }
  // Step 8: the relaxation is over after `iteration` (counted from 1), `s` being the record
  // after it: the interior has settled as a whole and no node still moves far (waiting for the
  // last annealing node to stop costs hundreds of iterations and no quality), or the farthest
  // move has stopped falling for `patience` settled steps; or, where rms_patience is set, the
  // rms move has made no progress for that many steps.
  MESHD_HD bool converged(const StepResult& r, int iteration, const Settling& s) const {
    if (iteration < min_iterations) return false;
    if (rms_patience > 0 && s.rms_stalled >= rms_patience) return true;
    return r.rms_move < dptol &&
           (r.max_move < max_move_factor * dptol || (patience > 0 && s.stalled >= patience));
  }
  // Where a run of several steps must hand back to the loop.
  MESHD_HD bool stops(const StepResult& r, int iteration, const Settling& s) const {
    return needs_triangulation(r.max_drift) || converged(r, iteration, s);
  }
};

}  // namespace meshd
