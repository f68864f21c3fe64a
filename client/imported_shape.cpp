#include "client/imported_shape.h"

namespace meshd::cli {

// Here rather than in gis_import.cpp, which a build without GDAL leaves out.
int64_t ImportedLayer::vertices() const {
  int64_t n = 0;
  for (const ImportedPolygon& p : polygons) {
    n += static_cast<int64_t>(p.outer.size());
    for (const auto& hole : p.holes) n += static_cast<int64_t>(hole.size());
  }
  return n;
}

namespace {

void set_polygon(const std::vector<Vec2>& ring, v1::Shape& shape) {
  auto* polygon = shape.mutable_polygon();
  polygon->mutable_vertices()->Reserve(static_cast<int>(ring.size()));
  for (const Vec2 p : ring) {
    v1::Vec2* v = polygon->add_vertices();
    v->set_x(p.x);
    v->set_y(p.y);
  }
}

void set_imported_polygon(const ImportedPolygon& p, v1::Shape& shape) {
  if (p.holes.empty()) {
    set_polygon(p.outer, shape);
    return;
  }
  auto* difference = shape.mutable_difference();
  set_polygon(p.outer, *difference->mutable_base());
  for (const auto& hole : p.holes) set_polygon(hole, *difference->add_subtract());
}

// Depth first through every operation; a placeholder has no kind, so it has no children.
int replace_in(v1::Shape& shape, const std::string& name, const v1::Shape& with) {
  switch (shape.kind_case()) {
    case v1::Shape::KIND_NOT_SET:
      if (shape.name() != name) return 0;
      shape = with;
      return 1;
    case v1::Shape::kUnion: {
      int n = 0;
      for (auto& s : *shape.mutable_union_()->mutable_shapes()) n += replace_in(s, name, with);
      return n;
    }
    case v1::Shape::kIntersection: {
      int n = 0;
      for (auto& s : *shape.mutable_intersection()->mutable_shapes())
        n += replace_in(s, name, with);
      return n;
    }
    case v1::Shape::kDifference: {
      auto* d = shape.mutable_difference();
      int n = d->has_base() ? replace_in(*d->mutable_base(), name, with) : 0;
      for (auto& s : *d->mutable_subtract()) n += replace_in(s, name, with);
      return n;
    }
    case v1::Shape::kTranslate:
      return shape.translate().has_shape()
                 ? replace_in(*shape.mutable_translate()->mutable_shape(), name, with)
                 : 0;
    case v1::Shape::kRotate:
      return shape.rotate().has_shape()
                 ? replace_in(*shape.mutable_rotate()->mutable_shape(), name, with)
                 : 0;
    case v1::Shape::kScale:
      return shape.scale().has_shape()
                 ? replace_in(*shape.mutable_scale()->mutable_shape(), name, with)
                 : 0;
    default:
      return 0;  // a primitive
  }
}

}  // namespace

v1::Shape imported_shape(const ImportedLayer& layer, const std::string& name) {
  v1::Shape shape;
  if (layer.polygons.size() == 1) {
    set_imported_polygon(layer.polygons[0], shape);
  } else {
    auto* shapes = shape.mutable_union_()->mutable_shapes();
    shapes->Reserve(static_cast<int>(layer.polygons.size()));
    for (const ImportedPolygon& p : layer.polygons) set_imported_polygon(p, *shapes->Add());
  }
  shape.set_name(name);
  return shape;
}

int replace_placeholders(v1::MeshRequest& request, const std::string& name,
                         const v1::Shape& shape) {
  int n = request.has_geometry() ? replace_in(*request.mutable_geometry(), name, shape) : 0;
  if (!request.has_size()) return n;
  for (auto& term : *request.mutable_size()->mutable_terms()) {
    if (term.has_distance() && term.distance().has_shape())
      n += replace_in(*term.mutable_distance()->mutable_shape(), name, shape);
  }
  return n;
}

}  // namespace meshd::cli
