#include "server/event_stream.h"

#include <chrono>
#include <utility>

#include "core/common/error.h"
#include "server/wire_message.h"

namespace meshd {

EventStream::EventStream(grpc::CallbackServerContext* context, JobManager& manager,
                         std::shared_ptr<Job> job, bool owns_job, Metrics& metrics)
    : context_(context),
      manager_(manager),
      job_(std::move(job)),
      owns_job_(owns_job),
      metrics_(metrics) {
  metrics_.add_streams(1);
  link_->stream = this;
  job_->subscribe(link_);
}

void EventStream::Link::wake() {
  std::lock_guard lock(mutex);
  if (stream != nullptr) stream->pump();
}

void EventStream::pump() {
  if (writing_ || finished_) return;
  grpc::Status status;
  switch (job_->next_event(cursor_, event_, status)) {
    case NextEvent::kNone:
      return;
    case NextEvent::kEvent:
      try {
        event_bytes_ = serialize_message(event_);
      } catch (const Error& e) {
        finish(grpc::Status(grpc::StatusCode::INTERNAL, e.what()));
        return;
      }
      writing_ = true;
      StartWrite(&event_bytes_);
      return;
    case NextEvent::kFinished:
      finish(status);
      return;
  }
}

void EventStream::finish(const grpc::Status& status) {
  if (finished_) return;
  finished_ = true;
  Finish(status);
}

void EventStream::cancel_job() {
  if (!owns_job_) return;
  const bool deadline = context_->deadline() <= std::chrono::system_clock::now();
  try {
    manager_.cancel(
        job_->id(),
        deadline ? grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED, "the call's deadline passed")
                 : grpc::Status(grpc::StatusCode::CANCELLED, "the client cancelled the call"));
  } catch (const Error&) {
    // Already finished and forgotten: nothing left to cancel.
  }
}

void EventStream::OnWriteDone(bool ok) {
  if (!ok) cancel_job();  // the client is gone
  std::lock_guard lock(link_->mutex);
  writing_ = false;
  if (!ok) {
    finish(grpc::Status(grpc::StatusCode::CANCELLED, "the stream broke"));
    return;
  }
  pump();
}

void EventStream::OnCancel() {
  cancel_job();
  std::lock_guard lock(link_->mutex);
  // A write in flight completes with ok = false and finishes there.
  if (!writing_) finish(grpc::Status(grpc::StatusCode::CANCELLED, "the call was cancelled"));
}

void EventStream::OnDone() {
  {
    std::lock_guard lock(link_->mutex);
    link_->stream = nullptr;
  }
  metrics_.add_streams(-1);
  delete this;
}

}  // namespace meshd
