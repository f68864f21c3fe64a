// What the plane's and the volume's optimizers (optimize_worst.cpp, optimize_slivers3d.cpp) share
// in their pattern search: a node tries steps of one length in a few directions, moves while a
// step improves its star, then halves the length.
#pragma once

namespace meshd {

// Moves at one step length at most: along a crease or at a corner the projection onto the
// boundary can shorten a step to a creep that still improves the star (a rim node of a coarse
// graded cylinder crept 3e-10 a move, for millions of moves: tests/fuzz/FINDINGS.md, F18); sound
// moves at a length take far fewer, since each travels the length.
constexpr int kMovesPerStepLength = 8;

}  // namespace meshd
