// How meshctl shows a job's events: a progress bar on a terminal, plain lines elsewhere, or one
// JSON object per event (--json); and the summary at the end.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "meshd/v1/service.pb.h"

namespace meshd::cli {

class EventView {
 public:
  enum class Mode { kBar, kLines, kJson };

  // kBar when stderr is a terminal, else kLines; kJson when asked.
  static Mode mode_for(bool json);

  explicit EventView(Mode mode) : mode_(mode) {}

  void show(const v1::MeshEvent& event);
  // The closing summary of a succeeded job (text modes only; JSON has the done event).
  void summary(const v1::Done& done, const std::string& job_id);
  // Clears the bar line before an error message.
  void end_line();

 private:
  void bar(const v1::Progress& p);

  Mode mode_;
  std::string backend_;
  bool bar_drawn_ = false;
  std::chrono::steady_clock::time_point last_line_{};
};

// The event as one line of JSON (proto field names), with result chunks' bytes left out.
std::string event_json(const v1::MeshEvent& event);

}  // namespace meshd::cli
