// Every DistMesh constant in one place, as in distmesh2d.m. Lengths are relative to h0.
#pragma once

#include <cstdint>

namespace meshd {

struct Params {
  double dptol = 0.001;   // stop when every interior node moved less than dptol * h0
  double ttol = 0.1;      // retriangulate when a node moved more than ttol * h0 since the last
  double fscale = 1.2;    // L0 = Fscale * (scaled size): bars push until this much longer
  double deltat = 0.2;    // Euler step
  double geps = 0.001;    // "inside" tolerance on the distance: geps * h0
  double deps = 1.4901161193847656e-08;  // finite-difference step of the gradient: deps * h0
  int density_control_interval = 30;     // iterations between density checks; 0 turns it off
  int max_iterations = 10000;            // hard cap; the result says whether it converged
  bool cleanup = true;  // boundary and corner clean-up after convergence
};

}  // namespace meshd
