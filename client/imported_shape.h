// An imported polygon layer (gis_import.h) as a CSG shape of a request, and the placeholders of
// a request file that stand for it.
#pragma once

#include <string>

#include "client/gis_import.h"
#include "meshd/v1/request.pb.h"

namespace meshd::cli {

// The layer as one shape: the union of its polygons (a lone polygon stands alone), each polygon
// with holes as difference(outer ring, holes...). `name` (letters, digits, '_', '-', '.') names
// the boundary group of every primitive in it. `layer` must hold at least one polygon.
v1::Shape imported_shape(const ImportedLayer& layer, const std::string& name);

// Replaces every placeholder in `request` — a Shape with no kind whose name is `name` — by
// `shape`, in the geometry and in the size field's distance terms. Returns how many it replaced.
int replace_placeholders(v1::MeshRequest& request, const std::string& name, const v1::Shape& shape);

}  // namespace meshd::cli
