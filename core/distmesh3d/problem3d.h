// Everything one 3D mesh job needs, validated: a 3D request after the service's conversion
// layer (the twin of problem.h).
#pragma once

#include "core/distmesh3d/params3d.h"
#include "core/geometry3d/shape3d.h"
#include "core/geometry3d/size_field3.h"

namespace meshd {

struct Problem3 {
  Shape3 geometry;
  SizeField3 size;
  double h0 = 0.0;            // edge length where h(p) is at its smallest bound (size_range3); > 0
  bool auto_features = true;  // the primitives' corners and edges become fixed nodes
  Params3 params;             // the seed included
};

}  // namespace meshd
