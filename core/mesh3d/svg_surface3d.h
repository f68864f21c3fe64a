// An SVG picture of a tetrahedral mesh for reports and quick looks: its boundary triangles seen
// from above at an angle, the ones facing away left out and the rest painted back to front, each
// filled by the quality of its tetrahedron (quality_colours.h) and shaded by its tilt to the
// light, with a legend. Concave parts may show a face through a nearer one where their depth
// order is ambiguous; VTU in ParaView is the tool for a close look.
#pragma once

#include <ostream>

#include "core/mesh3d/tet_mesh.h"

namespace meshd {

struct SvgSurfaceOptions {
  int width_px = 800;    // picture width; the height follows the view's aspect ratio
  double margin = 0.03;  // blank border on each side, as a fraction of width_px
};

// Writes the picture of `mesh` (a finished mesh, tet_mesh.h: boundary faces outward). Throws
// Error(kInternal) when its indices are out of range (check_indices); an empty mesh gives an
// empty picture.
void write_svg_surface3d(const TetMesh& mesh, std::ostream& out,
                         const SvgSurfaceOptions& options = {});

}  // namespace meshd
