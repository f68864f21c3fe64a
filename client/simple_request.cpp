#include "client/simple_request.h"

#include <cctype>
#include <filesystem>
#include <utility>

#include "client/gis_import.h"
#include "client/imported_shape.h"
#include "client/request_file.h"
#include "client/sdf_grid_shape.h"
#include "client/size_grid.h"
#include "core/common/error.h"

namespace meshd::cli {

namespace {

// The shape flags as a CSG tree: the disk or rectangle, minus the hole.
v1::Shape shape_from_flags(const CliOptions& o) {
  v1::Shape outer;
  if (o.circle) {
    outer.mutable_circle()->set_radius(*o.circle);
    outer.set_name("outer");
  } else {
    auto* r = outer.mutable_rectangle();
    r->mutable_min()->set_x(-o.rectangle->first / 2);
    r->mutable_min()->set_y(-o.rectangle->second / 2);
    r->mutable_max()->set_x(o.rectangle->first / 2);
    r->mutable_max()->set_y(o.rectangle->second / 2);
    outer.set_name("outer");
  }
  if (!o.hole) return outer;
  v1::Shape shape;
  auto* difference = shape.mutable_difference();
  *difference->mutable_base() = outer;
  v1::Shape* hole = difference->add_subtract();
  hole->mutable_circle()->set_radius(*o.hole);
  hole->set_name("hole");
  return shape;
}

// --sphere R: a ball, minus the hole.
v1::Volume volume_from_flags(const CliOptions& o) {
  v1::Volume volume;
  v1::Shape3 outer;
  outer.mutable_sphere()->set_radius(*o.sphere);
  outer.set_name("outer");
  if (!o.hole) {
    *volume.mutable_geometry() = outer;
    return volume;
  }
  auto* difference = volume.mutable_geometry()->mutable_difference();
  *difference->mutable_base() = outer;
  v1::Shape3* hole = difference->add_subtract();
  hole->mutable_sphere()->set_radius(*o.hole);
  hole->set_name("hole");
  return volume;
}

// The default boundary-group name: the layer's name with what a group name may not hold
// replaced by '_', at most 64 characters.
std::string group_name(const std::string& layer) {
  std::string name = layer.substr(0, 64);
  for (char& c : name) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    if (!ok) c = '_';
  }
  return name.empty() ? "imported" : name;
}

// The import flags without --import are a mistake, not something to ignore.
void check_no_import_flags(const CliOptions& o) {
  const std::pair<bool, const char*> flags[] = {
      {!o.gis.layer.empty(), "--layer"},         {!o.gis.where.empty(), "--where"},
      {o.gis.clip.has_value(), "--clip"},        {o.simplify.has_value(), "--simplify"},
      {!o.gis.from_crs.empty(), "--from-crs"},   {!o.gis.to_crs.empty(), "--to-crs"},
      {!o.import_name.empty(), "--import-name"}, {o.subtract_from_clip, "--subtract-from-clip"},
      {o.grade.has_value(), "--grade"}};
  for (const auto& [given, flag] : flags) {
    if (given) throw_invalid(flag, "only with --import FILE");
  }
}

// --import: the imported shape becomes the geometry (or the clip box minus it), or fills the
// request file's placeholders.
void import_into(const CliOptions& o, v1::MeshRequest& request, std::string* summary) {
  if (o.subtract_from_clip && !o.gis.clip)
    throw_invalid("--subtract-from-clip", "needs --clip xmin,ymin,xmax,ymax");
  if (o.subtract_from_clip && !o.args.empty()) {
    throw_invalid("--subtract-from-clip",
                  "only without a request file (a request file places the import with "
                  "placeholders)");
  }
  GisImportOptions gis = o.gis;
  if (o.simplify) {
    if (!(request.h0() > 0)) throw_invalid("--simplify", "needs h0 (--h0 or the request file's)");
    gis.simplify_tolerance = *o.simplify * request.h0();
  }
  const ImportedLayer layer = import_polygons(gis);
  const std::string name = o.import_name.empty() ? group_name(layer.layer) : o.import_name;
  const v1::Shape shape = imported_shape(layer, name);
  if (o.args.empty()) {
    if (!o.subtract_from_clip) {
      *request.mutable_geometry() = shape;
    } else {
      auto* difference = request.mutable_geometry()->mutable_difference();
      v1::Shape* box = difference->mutable_base();
      auto* r = box->mutable_rectangle();
      r->mutable_min()->set_x((*o.gis.clip)[0]);
      r->mutable_min()->set_y((*o.gis.clip)[1]);
      r->mutable_max()->set_x((*o.gis.clip)[2]);
      r->mutable_max()->set_y((*o.gis.clip)[3]);
      box->set_name("clip");
      *difference->add_subtract() = shape;
    }
  } else if (replace_placeholders(request, name, shape) == 0) {
    throw_invalid("request", o.args[0] + " has no placeholder for the import: a shape with only " +
                                 "name: \"" + name + "\" (no kind) where the outline goes");
  }
  if (o.grade) {
    // A size term about the same shape; the server judges the field's ratio against its limit.
    v1::DistanceSize* term = request.mutable_size()->add_terms()->mutable_distance();
    *term->mutable_shape() = shape;
    term->set_h_min((*o.grade)[0]);
    term->set_slope((*o.grade)[1]);
    term->set_h_max((*o.grade)[2]);
  }
  if (summary != nullptr) {
    size_t holes = 0;
    for (const auto& p : layer.polygons) holes += p.holes.size();
    auto count = [](size_t n, const char* what) {
      return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    *summary = "imported " + count(layer.polygons.size(), "polygon") + " (" + count(holes, "hole") +
               ", " + std::to_string(layer.vertices()) + " vertices) of " +
               count(static_cast<size_t>(layer.features), "feature") + " from " + o.gis.path +
               ", layer '" + layer.layer + "', as group '" + name + "' in " + layer.crs;
    if (layer.dropped_rings > 0) {
      *summary += "; dropped " + std::to_string(layer.dropped_rings) +
                  " degenerate rings (fewer than 3 distinct vertices, or no more area than the "
                  "simplification tolerance squared)";
    }
  }
}

// --sdf-grid stands alone: its placing flags need it, and it takes no other geometry.
void check_sdf_grid_flags(const CliOptions& o, bool shape, bool importing) {
  if (o.sdf_grid.empty()) {
    if (o.sdf_grid_origin) throw_invalid("--sdf-grid-origin", "only with --sdf-grid FILE.npy");
    if (o.sdf_grid_spacing) throw_invalid("--sdf-grid-spacing", "only with --sdf-grid FILE.npy");
    return;
  }
  if (shape || importing || !o.args.empty()) {
    throw_invalid("--sdf-grid",
                  "give it alone (with --h0), not with a request file, --circle, --rectangle or "
                  "--import");
  }
  if (!o.h0) throw_invalid("--h0", "required with --sdf-grid");
}

// --size-grid, --feature and --gradation add to the request's size field, whatever gave the
// geometry.
void add_size_flags(const CliOptions& o, v1::MeshRequest& request) {
  const SizeGridOptions& g = o.size_grid;
  if (g.path.empty()) {
    if (g.origin) throw_invalid("--size-grid-origin", "only with --size-grid FILE");
    if (g.spacing) throw_invalid("--size-grid-spacing", "only with --size-grid FILE");
  } else {
    *request.mutable_size()->add_terms()->mutable_grid() = read_size_grid(g);
  }
  if (o.feature) {
    auto* term = request.mutable_size()->add_terms()->mutable_feature();
    term->set_elements((*o.feature)[0]);
    term->set_h_min((*o.feature)[1]);
    term->set_h_max((*o.feature)[2]);
  }
  if (o.gradation) request.mutable_size()->set_gradation(*o.gradation);
}

}  // namespace

v1::MeshRequest build_request(const CliOptions& o, std::string* import_summary) {
  const bool importing = !o.gis.path.empty();
  if (!importing) check_no_import_flags(o);
  const bool shape = o.circle || o.rectangle || o.sphere;
  if (o.sphere && (o.circle || o.rectangle))
    throw_invalid("--sphere", "give --sphere, --circle or --rectangle, one of them");
  check_sdf_grid_flags(o, shape, importing);
  const bool grid = !o.sdf_grid.empty();
  if (importing && shape)
    throw_invalid("--import", "give --import or --circle/--rectangle, not both");
  if (importing && o.args.size() > 1)
    throw_invalid("request", "give at most one request file with --import");
  if (o.circle && o.rectangle) throw_invalid("--circle", "give --circle or --rectangle, not both");
  if (shape && !o.args.empty())
    throw_invalid("request", "give a request file or shape flags, not both");
  if (!shape && !importing && !grid && o.args.size() != 1) {
    throw_invalid("request",
                  "give one request file (REQUEST.textproto) or a shape (--circle R --h0 H)");
  }
  v1::MeshRequest request;
  if (grid) {
    // Its boundary group is named after the file, as an import's after its layer.
    *request.mutable_geometry() =
        sdf_grid_shape(o.sdf_grid, o.sdf_grid_origin.value_or(Vec2{0.0, 0.0}),
                       o.sdf_grid_spacing.value_or(Vec2{1.0, 1.0}),
                       group_name(std::filesystem::path(o.sdf_grid).stem().string()));
  } else if (shape) {
    if (!o.h0) throw_invalid("--h0", "required with --circle, --rectangle or --sphere");
    if (o.sphere)
      *request.mutable_volume() = volume_from_flags(o);
    else
      *request.mutable_geometry() = shape_from_flags(o);
  } else if (!o.args.empty()) {
    request = read_request_file(o.args[0]);
  } else if (!o.h0) {
    throw_invalid("--h0", "required with --import when no request file is given");
  }
  if (!shape && o.hole) throw_invalid("--hole", "only with --circle, --rectangle or --sphere");
  if (o.h0) request.set_h0(*o.h0);
  if (importing) import_into(o, request, import_summary);
  add_size_flags(o, request);
  if (o.seed) request.set_seed(*o.seed);
  v1::JobOptions& job = *request.mutable_options();
  if (o.backend) {
    job.set_backend(*o.backend == "gpu"   ? v1::JobOptions::BACKEND_GPU
                    : *o.backend == "cpu" ? v1::JobOptions::BACKEND_CPU
                                          : v1::JobOptions::BACKEND_AUTO);
  }
  if (o.priority) job.set_priority(*o.priority);
  if (o.snapshot_every)
    job.set_snapshot_every(static_cast<uint32_t>(*o.snapshot_every));
  else if (!o.frames_dir.empty() && job.snapshot_every() == 0)
    job.set_snapshot_every(10);
  if (o.timeout_s) job.set_timeout_s(*o.timeout_s);
  if (!o.label.empty()) job.set_label(o.label);
  return request;
}

}  // namespace meshd::cli
