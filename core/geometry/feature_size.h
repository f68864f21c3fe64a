// The local feature size of a domain on a grid: about k elements across its narrow parts.
//
// The feature size at p is |d(p)| + d_MA(p), d the signed distance to the boundary and d_MA the
// distance to the medial axis (the ridge of d, where points are as far from one wall as from
// another): in a channel of width w it is w / 2 everywhere across, so an edge of
// 2 (|d| + d_MA) / k puts k elements across it. On the grid the medial axis is the set of inside
// samples where the distance's central-difference gradient is short (|grad d| < kRidgeGradient;
// it is 1 elsewhere), and d_MA is the 16-neighbour path distance from them (gradation.h's
// limit_gradient with slope 1 from zeros on the axis), at most 3% long.
#pragma once

#include "core/common/vec2.h"
#include "core/geometry/program.h"
#include "core/geometry/size_field.h"

namespace meshd {

// Where |grad d| falls below this, a sample lies on (or within a cell of) the medial axis.
constexpr double kRidgeGradient = 0.8;

// The feature-size term sampled on a grid over `box`, spaced about `cell`: relative sizes
// clamp(2 (|d| + d_MA) / (elements * h0), h_min, h_max).
//   geometry  the domain's program (its distance d)
//   box       the domain's box, finite
//   cell      the wanted spacing, > 0: fine enough to see the narrowest channel that matters
//   h0        the request's h0, > 0 (the term's sizes are relative to it)
GridSize feature_size_grid(const Program& geometry, const FeatureSize& term, const Box& box,
                           double cell, double h0);

}  // namespace meshd
