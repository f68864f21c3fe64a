// The finish's removal of trapped nodes: free interior nodes with only three triangles.
//
// Where the size field changes fast, or density control leaves one node too many, DistMesh's
// forces can squeeze a node between three neighbours. It settles at their centre, its three
// angles near 120 degrees, and its three triangles measure about 0.4 wherever it moves: no node
// move mends them, so the worst-element optimisation cannot. Without the node, its neighbours
// form one triangle, near equilateral. Removing a node changes a Delaunay triangulation inside
// the node's star only, and three nodes have one triangulation, so the mesh stays the Delaunay
// triangulation of its remaining nodes.
#pragma once

#include <cstdint>

#include "core/distmesh/engine.h"

namespace meshd {

// Removes from `mesh` every node v >= nfix on no boundary half-edge that is a corner of exactly
// three triangles around it, replacing those three by the triangle of its neighbours (turned as
// the first of them was), and again while a removal leaves a neighbour with three. The removed
// points stay in mesh.points, used by no triangle (mesh.tidy becomes false); mesh.boundary
// follows the renumbered triangles, and mesh.below, when present, gains the new triangles.
// A star that is not a plain fan of three (a fold, or its centre outside its neighbours'
// triangle) is left alone. Returns the number of nodes removed; nothing, at once, where the engine
// found none (mesh.none_trapped).
int64_t remove_trapped_nodes(MeshCopy& mesh, int32_t nfix);

}  // namespace meshd
