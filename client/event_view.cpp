#include "client/event_view.h"

#include <google/protobuf/util/json_util.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace meshd::cli {

namespace {

std::string json(const google::protobuf::Message& message) {
  std::string out;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(message, &out, options);
  return out;
}

}  // namespace

EventView::Mode EventView::mode_for(bool json_output) {
  if (json_output) return Mode::kJson;
  return isatty(fileno(stderr)) ? Mode::kBar : Mode::kLines;
}

std::string event_json(const v1::MeshEvent& event) {
  if (!event.has_result_chunk()) return json(event);
  v1::MeshEvent copy = event;
  copy.mutable_result_chunk()->clear_data();
  return json(copy);
}

void EventView::end_line() {
  if (bar_drawn_) std::fputc('\n', stderr);
  bar_drawn_ = false;
}

void EventView::bar(const v1::Progress& p) {
  // The nodes have settled once the largest move falls to 0.01 h0 (10 dptol by default): fill
  // the bar along log(max move) from 1 h0 down to there.
  const double settled =
      p.max_move() > 0 ? std::clamp(std::log10(p.max_move()) / -2.0, 0.0, 1.0) : 1.0;
  constexpr int kWidth = 24;
  const int filled = static_cast<int>(settled * kWidth);
  std::fprintf(stderr, "\r[%s%s] iteration %d  max move %.1e h0  %lld nodes  %.2f s  %s\x1b[K",
               std::string(filled, '#').c_str(), std::string(kWidth - filled, '.').c_str(),
               p.iteration(), p.max_move(), static_cast<long long>(p.nodes()), p.elapsed_s(),
               backend_.c_str());
  bar_drawn_ = true;
}

void EventView::show(const v1::MeshEvent& e) {
  if (mode_ == Mode::kJson) {
    std::printf("%s\n", event_json(e).c_str());
    std::fflush(stdout);
    return;
  }
  if (e.has_queued()) {
    end_line();
    std::fprintf(stderr, "job %s queued (position %d)\n", e.job_id().c_str(),
                 e.queued().position());
  } else if (e.has_started()) {
    backend_ = e.started().device();
    end_line();
    std::fprintf(stderr, "started on %s after %.3f s in the queue\n", backend_.c_str(),
                 e.started().queue_wait_s());
  } else if (e.has_progress()) {
    if (mode_ == Mode::kBar) {
      bar(e.progress());
      return;
    }
    // Plain lines: at most one a second, for logs.
    const auto now = std::chrono::steady_clock::now();
    if (now - last_line_ < std::chrono::seconds(1)) return;
    last_line_ = now;
    const auto& p = e.progress();
    std::fprintf(stderr, "iteration %d  max move %.1e h0  %lld nodes  %.2f s\n", p.iteration(),
                 p.max_move(), static_cast<long long>(p.nodes()), p.elapsed_s());
  } else if (e.has_result_chunk() && e.result_chunk().index() == 0) {
    end_line();
  }
}

void EventView::summary(const v1::Done& d, const std::string& job_id) {
  if (mode_ == Mode::kJson) return;
  end_line();
  const auto& s = d.stats();
  const auto& q = d.quality();
  if (d.tetrahedra() > 0) {
    std::printf(
        "job %s done on %s\n"
        "  nodes %lld  tetrahedra %lld  iterations %d%s\n"
        "  time %.3f s (mesh %.3f s, queue %.3f s)\n"
        "  quality q_min %.3f  q_mean %.4f  dihedral angles %.1f to %.1f deg\n"
        "  volume %.6g  surface nodes off the boundary by at most %.2g\n",
        job_id.c_str(), d.device().c_str(), static_cast<long long>(d.nodes()),
        static_cast<long long>(d.tetrahedra()), s.iterations(),
        s.converged() ? "" : " (stopped at max_iterations: not converged)",
        s.t_mesh() + s.queue_wait_s(), s.t_mesh(), s.queue_wait_s(), q.q_min(), q.q_mean(),
        q.min_dihedral_deg(), q.max_dihedral_deg(), q.volume(), q.max_surface_offset());
    return;
  }
  std::printf(
      "job %s done on %s\n"
      "  nodes %lld  triangles %lld  iterations %d%s\n"
      "  time %.3f s (mesh %.3f s, queue %.3f s)\n"
      "  quality q_min %.3f  q_mean %.4f  min angle %.1f deg\n",
      job_id.c_str(), d.device().c_str(), static_cast<long long>(d.nodes()),
      static_cast<long long>(d.triangles()), s.iterations(),
      s.converged() ? "" : " (stopped at max_iterations: not converged)",
      s.t_mesh() + s.queue_wait_s(), s.t_mesh(), s.queue_wait_s(), q.q_min(), q.q_mean(),
      q.min_angle_deg());
}

}  // namespace meshd::cli
