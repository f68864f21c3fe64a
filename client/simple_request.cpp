#include "client/simple_request.h"

#include "client/request_file.h"
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

}  // namespace

v1::MeshRequest build_request(const CliOptions& o) {
  const bool shape = o.circle || o.rectangle;
  if (o.circle && o.rectangle) throw_invalid("--circle", "give --circle or --rectangle, not both");
  if (shape && !o.args.empty())
    throw_invalid("request", "give a request file or shape flags, not both");
  if (!shape && o.args.size() != 1) {
    throw_invalid("request",
                  "give one request file (REQUEST.textproto) or a shape (--circle R --h0 H)");
  }
  v1::MeshRequest request;
  if (shape) {
    if (!o.h0) throw_invalid("--h0", "required with --circle or --rectangle");
    *request.mutable_geometry() = shape_from_flags(o);
  } else {
    request = read_request_file(o.args[0]);
    if (o.hole) throw_invalid("--hole", "only with --circle or --rectangle");
  }
  if (o.h0) request.set_h0(*o.h0);
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
