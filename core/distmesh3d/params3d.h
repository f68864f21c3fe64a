// Every constant of the 3D DistMesh loop in one place, as in distmeshnd.m. Lengths are relative
// to h0.
#pragma once

#include <cstdint>

namespace meshd {

struct Params3 {
  // Termination: the root-mean-square move of the interior nodes (d < -geps) in one step is
  // under dptol and the largest under max_move_factor dptol, or the rms alone once the largest
  // has stopped falling for `patience` such steps (StepRule, step_rule.cuh, as in 2D). Moves are
  // measured in each node's own edge length (the mean desired length of its bars).
  double dptol = 0.001;
  double max_move_factor = 10.0;
  int patience = 100;
  double ttol = 0.1;    // retriangulate when a node drifted this far since the last one
  double fscale = 1.1;  // distmeshnd's L0mult = 1 + 0.4 / 2^(dim - 1)
  double deltat = 0.1;  // distmeshnd's Euler step
  // Heavy-ball momentum: each step adds momentum times the previous one (0: distmeshnd's plain
  // Euler step).
  double momentum = 0.0;
  // "Inside" tolerance on the distance (geps h0): a tetrahedron is kept when the distance at its
  // centroid is under -geps, and a node is interior when its distance is. distmeshnd's 0.1.
  double geps = 0.1;
  double deps = 1.4901161193847656e-08;  // finite-difference step of the gradient: deps h0
  int density_control_interval = 30;     // iterations between density checks; 0 turns it off
  int max_iterations = 2000;             // hard cap; the result says whether it converged
  uint64_t seed = 1;                     // the size-based rejection of the initial points
  bool optimize_slivers = true;          // the finish (optimize_slivers3d.h)
};

}  // namespace meshd
