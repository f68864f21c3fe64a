// An SVG picture of a mesh for reports and quick looks: triangles filled by quality, thin
// edges, thicker boundary edges coloured by group, and a legend.
//
// Size stays proportional to the triangle count and small per triangle: coordinates are
// integers on a 1/10 px grid, each triangle is one relative "M x y l dx dy dx dy z" run, and
// triangles share a <path> per quality bin (split every 10,000 triangles, which keeps XML
// parsers' attribute limits happy) instead of one element each: about 20 bytes per triangle, so
// some 20 MB at a million triangles. Edges are drawn only while triangles are
// large enough on the page for them to be seen.
#pragma once

#include <ostream>

#include "core/mesh/mesh.h"

namespace meshd {

struct SvgOptions {
  int width_px = 800;    // picture width; the height follows the mesh's aspect ratio
  double margin = 0.03;  // blank border on each side, as a fraction of width_px
  bool legend = true;    // colour bar with q_min and q_mean, and boundary group names
};

// Writes an SVG picture of mesh, y axis up. Fill colour by radius ratio q in 20 bins from red
// (q = 0) through yellow and green to blue (q = 1). Throws Error(kInternal) when the mesh's
// indices are out of range; an empty mesh gives an empty picture.
//
// mesh: #N points, #M triangles, #E boundary edges; any length unit (the picture is fitted).
// out: any output stream.
void write_svg(const Mesh& mesh, std::ostream& out, const SvgOptions& options = {});

}  // namespace meshd
