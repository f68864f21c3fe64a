// A closed triangle surface as a signed-distance primitive (a polyhedron of a request): its
// triangles in a bounding-volume hierarchy for the distance, and angle-weighted pseudonormals
// for the sign.
//
// Invariants of a built surface: the triangles form a closed, consistently oriented 2-manifold
// (every edge used by exactly two triangles, in opposite directions), turned outward (positive
// enclosed volume; a surface given inward is turned), none of zero area. Under those, the sign of
// (p - c) . n, with c the nearest surface point and n the pseudonormal of the face, edge or vertex
// c lies on, is the side p is on (Baerentzen and Aanaes, 2005): the distance is exact and its
// sign agrees with the winding number everywhere off the surface. A surface that crosses itself
// (or touches itself at a vertex) has no meaningful inside and is refused
// (surface_self_intersection3.h).
//
// The arrays are flat, and TriangleSurface3View points at them, so that the evaluator
// (surface_sdf3.cuh) reads them on the host and on the device alike.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

// A node of the triangles' hierarchy: a leaf covers triangles [first, last) in tree order; an
// inner node's children are nodes `first` and `last`. At most kMaxSurfaceBvhDepth levels.
struct SurfaceBvhNode {
  Box3 box;
  uint32_t first;
  uint32_t last;
  uint32_t leaf;
  uint32_t unused = 0;
};

constexpr int kMaxSurfaceBvhDepth = 40;

// Where the nearest point of a triangle lies, which picks the pseudonormal for the sign.
enum SurfaceRegion : int { kOnFace = 0, kOnEdgeAB, kOnEdgeBC, kOnEdgeCA, kOnA, kOnB, kOnC };

struct TriangleSurface3View {
  const Vec3* vertices;          // #V
  const Vec3* vertex_normals;    // #V, angle-weighted
  const int32_t* triangles;      // 3 per triangle, in tree order
  const Vec3* triangle_normals;  // 4 per triangle: the face's, then its edges' ab, bc, ca
  const SurfaceBvhNode* nodes;
  uint32_t root;
};

struct TriangleSurface3 {
  std::vector<Vec3> vertices;
  std::vector<Vec3> vertex_normals;
  std::vector<int32_t> triangles;
  std::vector<Vec3> triangle_normals;
  std::vector<SurfaceBvhNode> nodes;
  uint32_t root = 0;
  Box3 box;
  // The edges where the two triangles' normals differ by more than kSharpSurfaceAngleDeg, as
  // vertex pairs: the sharp edges DistMesh keeps (sharp_features3.h).
  std::vector<std::array<int32_t, 2>> sharp_edges;

  TriangleSurface3View view() const {
    return {vertices.data(),         vertex_normals.data(), triangles.data(),
            triangle_normals.data(), nodes.data(),          root};
  }
};

// Faces meeting at more than this angle between their normals make a sharp edge: a faceted
// solid's (an icosahedron's, 41.8 degrees) are, a finely tessellated curve's are not.
constexpr double kSharpSurfaceAngleDeg = 35.0;

// Builds the surface over `vertices` (world coordinates) and `triangles` (indices into them).
// Throws Error(kInvalidArgument) naming `path` + ".vertices" or ".triangles" and the first
// offending triangle or edge: fewer than 4 triangles, an index out of range, a triangle of zero
// area, an edge not used exactly twice in opposite directions (open, non-manifold or
// inconsistently oriented), two triangles that cross, a surface enclosing no volume.
TriangleSurface3 build_triangle_surface3(std::vector<Vec3> vertices,
                                         const std::vector<std::array<int32_t, 3>>& triangles,
                                         const std::string& path);

}  // namespace meshd
