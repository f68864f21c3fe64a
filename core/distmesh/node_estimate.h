// The expected node count of a DistMesh mesh, before meshing: an equilateral mesh has about
// N = (2 / sqrt(3)) * integral over the domain of 1 / (h0 h(p))^2 dA nodes.
#pragma once

#include "core/distmesh/problem.h"

namespace meshd {

// Estimated node count of `problem`'s mesh (midpoint-rule integral on a grid over the box).
// Throws Error(kInvalidArgument) naming "geometry" when the domain is empty.
double estimate_node_count(const Problem& problem);

struct CompiledProblem;
class ThreadPool;

// The same from `problem`'s inverse_size_integral once surveyed, else from a survey: samples
// over pool's threads (the caller's thread alone when null), the same number on any number.
double estimate_node_count(const CompiledProblem& problem, ThreadPool* pool = nullptr);

// What one pass of samples over the domain tells before meshing.
struct DomainSurvey {
  double nodes;  // estimate_node_count
  double depth;  // the greatest distance from the boundary of a sample inside: the domain's
                 // half-thickness where it is thickest, from below (the CSG distances understate)
  double inverse_size;  // CompiledProblem::inverse_size_integral
};
DomainSurvey survey_domain(const CompiledProblem& problem, ThreadPool* pool = nullptr);

// The h0 that aims `problem` at about `nodes` nodes (N scales as 1 / h0^2).
double h0_for_node_count(const Problem& problem, double nodes);

}  // namespace meshd
