// Exact geometric predicates on double coordinates (CGAL's filtered predicates): the reference
// that the lawson repair on the host uses, and the fallback the GPU filter defers to when its
// error bound cannot decide.
#pragma once

#include "core/common/vec2.h"
#include "core/common/vec3.h"

namespace meshd {

// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear.
int orientation_sign(Vec2 a, Vec2 b, Vec2 c);
// +1 when d lies strictly inside the circle through the counter-clockwise a, b, c; -1 outside;
// 0 on it.
int in_circle_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d);
// +1 when (b - a) . ((c - a) x (d - a)) > 0 (delaunay3d.h's positive orientation), -1 when < 0,
// 0 coplanar.
int orientation3_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d);
// +1 when e lies strictly inside the sphere through the positively oriented a, b, c, d; -1
// outside; 0 on it.
int in_sphere_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 e);

}  // namespace meshd
