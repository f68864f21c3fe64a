#include "server/mesh_service.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <functional>

#include "core/common/error.h"
#include "server/event_stream.h"
#include "server/status_mapping.h"
#include "server/wire_message.h"

namespace meshd {

namespace {

// The call's deadline on the job clock; max() when the client set none.
Job::Clock::time_point job_deadline(const grpc::CallbackServerContext& context) {
  const auto deadline = context.deadline();
  const auto now = std::chrono::system_clock::now();
  if (deadline >= now + std::chrono::hours(24 * 365)) return Job::Clock::time_point::max();
  return Job::Clock::now() + std::chrono::duration_cast<Job::Clock::duration>(deadline - now);
}

grpc::ServerUnaryReactor* finish_unary(grpc::CallbackServerContext* context,
                                       const grpc::Status& status) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  reactor->Finish(status);
  return reactor;
}

// Parses the request, runs `body` on it and finishes the call with OK and the reply it returns,
// or, after `on_error` (when given), with the status its error maps to.
template <typename Request, typename Body>
grpc::ServerUnaryReactor* unary(grpc::CallbackServerContext* context, const BearerToken& token,
                                const grpc::ByteBuffer* request, grpc::ByteBuffer* reply,
                                Body&& body, const std::function<void()>& on_error = {}) {
  if (grpc::Status status = token.check(*context); !status.ok())
    return finish_unary(context, status);
  try {
    *reply = serialize_message(body(parse_message<Request>(*request)));
    return finish_unary(context, grpc::Status::OK);
  } catch (...) {
    if (on_error) on_error();
    return finish_unary(context, to_grpc_status(std::current_exception()));
  }
}

}  // namespace

// A request that cannot be parsed counts as rejected, as one that fails validation does.
grpc::ServerWriteReactor<grpc::ByteBuffer>* MeshService::Generate(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* request) {
  if (grpc::Status status = token_.check(*context); !status.ok()) return new RefusedStream(status);
  try {
    const auto mesh_request = parse_message<v1::MeshRequest>(*request);
    std::shared_ptr<Job> job = manager_.submit(mesh_request, job_deadline(*context));
    return new EventStream(context, manager_, std::move(job), /*owns_job=*/true, metrics_);
  } catch (...) {
    metrics_.count_job("rejected");
    const grpc::Status status = to_grpc_status(std::current_exception());
    spdlog::info("Generate refused from {}: {}", context->peer(), status.error_message());
    return new RefusedStream(status);
  }
}

grpc::ServerUnaryReactor* MeshService::Submit(grpc::CallbackServerContext* context,
                                              const grpc::ByteBuffer* request,
                                              grpc::ByteBuffer* reply) {
  return unary<v1::MeshRequest>(
      context, token_, request, reply,
      [&](const v1::MeshRequest& mesh_request) {
        v1::JobRef ref;
        ref.set_job_id(manager_.submit(mesh_request, Job::Clock::time_point::max())->id());
        return ref;
      },
      [&] { metrics_.count_job("rejected"); });
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* MeshService::Watch(grpc::CallbackServerContext* context,
                                                               const grpc::ByteBuffer* request) {
  if (grpc::Status status = token_.check(*context); !status.ok()) return new RefusedStream(status);
  try {
    const auto ref = parse_message<v1::JobRef>(*request);
    return new EventStream(context, manager_, manager_.find(ref.job_id()), /*owns_job=*/false,
                           metrics_);
  } catch (...) {
    return new RefusedStream(to_grpc_status(std::current_exception()));
  }
}

grpc::ServerUnaryReactor* MeshService::Cancel(grpc::CallbackServerContext* context,
                                              const grpc::ByteBuffer* request,
                                              grpc::ByteBuffer* reply) {
  return unary<v1::JobRef>(context, token_, request, reply, [&](const v1::JobRef& ref) {
    return manager_.cancel(ref.job_id(),
                           grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by Cancel"));
  });
}

grpc::ServerUnaryReactor* MeshService::GetJob(grpc::CallbackServerContext* context,
                                              const grpc::ByteBuffer* request,
                                              grpc::ByteBuffer* reply) {
  return unary<v1::JobRef>(context, token_, request, reply, [&](const v1::JobRef& ref) {
    return manager_.find(ref.job_id())->info();
  });
}

grpc::ServerUnaryReactor* MeshService::ListJobs(grpc::CallbackServerContext* context,
                                                const grpc::ByteBuffer* request,
                                                grpc::ByteBuffer* reply) {
  return unary<v1::ListJobsRequest>(context, token_, request, reply,
                                    [&](const v1::ListJobsRequest& list) {
                                      v1::ListJobsResponse jobs;
                                      for (v1::JobInfo& info : manager_.list(list.state()))
                                        *jobs.add_jobs() = std::move(info);
                                      return jobs;
                                    });
}

}  // namespace meshd
