// Every DistMesh constant in one place, as in distmesh2d.m. Lengths are relative to h0.
#pragma once

#include <cstdint>

namespace meshd {

// The force scale fscale for a size field the request leaves it unset for (Params::fscale_auto).
constexpr double kUniformFscale = 1.2;  // distmesh2d.m's
constexpr double kGradedFscale = 1.1;

struct Params {
  // Moves are measured in each node's own edge length, h0 * h (step_rule.cuh); for a uniform
  // field that is h0, as in distmesh2d.m.
  // Termination: the root-mean-square move of the interior nodes (d < -geps) in one step is
  // under dptol and the largest under 10 dptol, or the rms alone once the largest has not
  // fallen for 100 such steps (a node cycling between two triangulations never stops;
  // step_rule.cuh). distmesh2d.m waits for the largest move alone; on G2 that takes ~10x the
  // iterations for a q_mean 0.001 higher.
  double dptol = 0.001;
  double ttol = 0.1;               // retriangulate when a node moved more than ttol since the last
  double fscale = kUniformFscale;  // L0 = Fscale * (scaled size): bars push until this much longer
  // Unset in the request: compile_problem keeps distmesh2d.m's 1.2 for a uniform size field and
  // takes 1.1 for a graded one (the constants above). Measured at 100k nodes, G5 and
  // plate_with_holes reach q_mean 0.993-0.995 with 1.1 against 0.984-0.988 with 1.2; a uniform
  // field's boundary layer needs the stronger push (G1 with 1.1: q_min 0.40).
  bool fscale_auto = true;
  double deltat = 0.2;  // Euler step
  // Heavy-ball momentum: each step adds momentum times the previous one. 0 is distmesh2d.m's
  // plain Euler step; 0.5 cuts the iterations about 3x at equal quality.
  double momentum = 0.5;
  double geps = 0.001;                   // "inside" tolerance on the distance: geps * h0
  double deps = 1.4901161193847656e-08;  // finite-difference step of the gradient: deps * h0
  int density_control_interval = 30;     // iterations between density checks; 0 turns it off
  int max_iterations = 10000;            // hard cap; the result says whether it converged
  bool cleanup = true;                   // boundary and corner clean-up after convergence
  // Mesh at h0 * 2^k first and refine by midpoints (refine.h) when the mesh is large. kAuto
  // does so for graded size fields only: there the multilevel start replaces the one of the
  // size-based rejection (G5 at 10k: 1.4x faster, q_mean 0.983 instead of 0.980, measured
  // against an independent draw per point); a uniform field's equilateral start is better than
  // any refined one (G1: q_mean 0.9975 against 0.996).
  enum class Multilevel { kAuto, kOn, kOff };
  Multilevel multilevel = Multilevel::kAuto;
};

}  // namespace meshd
