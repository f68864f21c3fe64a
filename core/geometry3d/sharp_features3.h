// The points on a 3D domain's sharp corners and edges, which DistMesh keeps fixed so that its
// mesh keeps them sharp: a node that only follows the distance's gradient slides off a corner
// and rounds an edge.
//
// Only the primitives' own features count: a cuboid's 8 corners and 12 edges, the rims of a
// cylinder and of a frustum (each end with a radius > 0) and a cone's apex, an extrusion's two
// rims (its profile's boundary, boundary_samples.h) and a vertical edge at each corner of the
// profile, a revolution's rim at each corner of its profile (an apex on the axis), a polyhedron's
// edges where its faces meet at more than kSharpSurfaceAngleDeg (in chains), sampled along
// each edge and kept where they lie on the final domain's boundary. Edges that CSG creates where
// two primitives' surfaces meet (a sphere cutting a cuboid's face, two cylinders crossing) are
// crease_features3.h's.
#pragma once

#include <cstddef>
#include <vector>

#include "core/common/vec3.h"
#include "core/geometry3d/program3d.h"

namespace meshd {

// More sharp-feature points than this is a request error: the mesh they imply (1/spacing^3
// nodes around them) is far beyond any job's limits.
constexpr size_t kMaxSharpFeaturePoints = 1'000'000;

// The fixed points of `program`'s sharp features, #F by 3, in world coordinates, without
// duplicates: the corners, then samples along each sharp edge, at most `spacing` apart along
// it (a rim has at least 3), each edge's ends at its corners. Only points where the whole
// program's distance is 0 (within 1e-9 spacing, plus rounding) are kept: features removed or
// buried by CSG drop out. spacing > 0 in length units: h0 times the relative size there, as the
// caller chooses. Throws Error(kInvalidArgument) naming a primitive's path when the features
// would need more than kMaxSharpFeaturePoints points; Error(kInternal) for a bad spacing.
std::vector<Vec3> sharp_features3(const Program3& program, double spacing);

}  // namespace meshd
