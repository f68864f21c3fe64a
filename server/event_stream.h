// The server side of one Generate or Watch stream: a write reactor that pulls the job's events
// at the pace of its reader (one write in flight; the next event is taken when it completes),
// so that a slow reader costs the server one event, never a backlog.
//
// A Generate stream owns its job: the call's cancellation, deadline or the client's
// disconnection cancels the job. A Watch stream only reads.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>

#include "meshd/v1/service.pb.h"
#include "server/job_manager.h"
#include "server/metrics.h"

namespace meshd {

class EventStream final : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  EventStream(grpc::CallbackServerContext* context, JobManager& manager, std::shared_ptr<Job> job,
              bool owns_job, Metrics& metrics);

  void OnWriteDone(bool ok) override;
  void OnCancel() override;
  void OnDone() override;

 private:
  // The job wakes the stream through this link; OnDone cuts it, under the same mutex, so that
  // a late wake never reaches a deleted stream.
  struct Link final : JobSubscriber {
    std::mutex mutex;
    EventStream* stream = nullptr;
    void wake() override;
  };

  void pump();                              // link_->mutex held
  void finish(const grpc::Status& status);  // link_->mutex held
  void cancel_job();

  grpc::CallbackServerContext* const context_;
  JobManager& manager_;
  const std::shared_ptr<Job> job_;
  const bool owns_job_;
  Metrics& metrics_;
  const std::shared_ptr<Link> link_ = std::make_shared<Link>();
  EventCursor cursor_;
  v1::MeshEvent event_;
  grpc::ByteBuffer event_bytes_;  // event_ serialized: the service's methods are raw
  bool writing_ = false;
  bool finished_ = false;
};

// A stream that ends at once with `status` (a refused request).
class RefusedStream final : public grpc::ServerWriteReactor<grpc::ByteBuffer> {
 public:
  explicit RefusedStream(const grpc::Status& status) { Finish(status); }
  void OnDone() override { delete this; }
};

}  // namespace meshd
