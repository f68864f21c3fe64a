// Gradient limiting of a size field (Persson, "Mesh size functions for implicit geometries and
// PDE-based gradient limiting", 2006; the "limgrad" of MESH2D and OceanMesh2D): the largest
// field that lies nowhere above the given one and grows by at most g per length unit.
//
// On a grid this is a shortest-path problem: h(p) = min over q of h(q) + g * dist(q, p). It is
// solved by sweeps over the rows, up and down, until no value falls (values are only ever
// lowered; gradation.cpp says why this ends where Dijkstra's order would). Paths run along the
// 16 nearest neighbours of a sample (the 8 adjacent ones and the 8 a knight's move away): a path
// over them is at most about 3% longer than the straight line (8 neighbours: 8%), so a
// point-like small size becomes a cone of slope g, rounded to a 16-gon whose sides are at most
// 3% above the cone.
#pragma once

#include <cstdint>
#include <string>

#include "core/common/vec2.h"
#include "core/geometry/size_field.h"
#include "core/geometry/size_program.h"

namespace meshd {

class ThreadPool;

// Lowers `grid.values` where needed so that between neighbours p, q (as above)
// h(p) <= h(q) + g * |p - q|. Never raises a value; a field that already complies is unchanged.
//   grid  nx * ny samples, spacing > 0
//   g     the largest growth of h per length unit of the grid's coordinates, > 0
void limit_gradient(GridSize& grid, double g);

// At most this many samples in a grid that the server samples a field on (about 1024 x 1024).
constexpr double kMaxGradationSamples = 1 << 20;

// A grid whose nodes span `box`, spaced about `cell` apart (more where that would exceed
// kMaxGradationSamples); its values are nx * ny zeros, its scale 1. Throws
// Error(kInvalidArgument) naming `field` when the box has no finite, positive width and height.
//   box   the domain's box
//   cell  the wanted spacing, > 0
GridSize grid_over(const Box& box, double cell, const std::string& field);

// `size` sampled at the nodes of a grid that spans `box`, spaced about `cell` apart (more where
// that would exceed kMaxGradationSamples), then limited to a growth of g per length unit. The
// samples are stored relative to the field's lower bound (GridSize::scale), so that single
// precision holds them whatever the field's magnitude.
//   box   finite, non-empty
//   cell  the wanted spacing, > 0 (the finest edge / 2 for a mesh)
//   g     the largest growth of h per length unit, > 0
//   pool  threads for the samples, or null for the caller's thread alone
GridSize limited_size_grid(const SizeProgram& size, const Box& box, double cell, double g,
                           ThreadPool* pool = nullptr);

}  // namespace meshd
