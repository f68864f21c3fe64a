#include "server/mesh_service.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "core/common/error.h"
#include "server/event_stream.h"
#include "server/status_mapping.h"

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

// Runs `body` and finishes the call with OK, or with the status its error maps to.
template <typename Body>
grpc::ServerUnaryReactor* unary(grpc::CallbackServerContext* context, const BearerToken& token,
                                Body&& body) {
  if (grpc::Status status = token.check(*context); !status.ok())
    return finish_unary(context, status);
  try {
    body();
    return finish_unary(context, grpc::Status::OK);
  } catch (...) {
    return finish_unary(context, to_grpc_status(std::current_exception()));
  }
}

}  // namespace

grpc::ServerWriteReactor<v1::MeshEvent>* MeshService::Generate(grpc::CallbackServerContext* context,
                                                               const v1::MeshRequest* request) {
  if (grpc::Status status = token_.check(*context); !status.ok()) return new RefusedStream(status);
  try {
    std::shared_ptr<Job> job = manager_.submit(*request, job_deadline(*context));
    return new EventStream(context, manager_, std::move(job), /*owns_job=*/true, metrics_);
  } catch (...) {
    metrics_.count_job("rejected");
    const grpc::Status status = to_grpc_status(std::current_exception());
    spdlog::info("Generate refused from {}: {}", context->peer(), status.error_message());
    return new RefusedStream(status);
  }
}

grpc::ServerUnaryReactor* MeshService::Submit(grpc::CallbackServerContext* context,
                                              const v1::MeshRequest* request, v1::JobRef* reply) {
  return unary(context, token_, [&] {
    try {
      reply->set_job_id(manager_.submit(*request, Job::Clock::time_point::max())->id());
    } catch (...) {
      metrics_.count_job("rejected");
      throw;
    }
  });
}

grpc::ServerWriteReactor<v1::MeshEvent>* MeshService::Watch(grpc::CallbackServerContext* context,
                                                            const v1::JobRef* request) {
  if (grpc::Status status = token_.check(*context); !status.ok()) return new RefusedStream(status);
  try {
    return new EventStream(context, manager_, manager_.find(request->job_id()),
                           /*owns_job=*/false, metrics_);
  } catch (...) {
    return new RefusedStream(to_grpc_status(std::current_exception()));
  }
}

grpc::ServerUnaryReactor* MeshService::Cancel(grpc::CallbackServerContext* context,
                                              const v1::JobRef* request, v1::JobInfo* reply) {
  return unary(context, token_, [&] {
    *reply = manager_.cancel(request->job_id(),
                             grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by Cancel"));
  });
}

grpc::ServerUnaryReactor* MeshService::GetJob(grpc::CallbackServerContext* context,
                                              const v1::JobRef* request, v1::JobInfo* reply) {
  return unary(context, token_, [&] { *reply = manager_.find(request->job_id())->info(); });
}

grpc::ServerUnaryReactor* MeshService::ListJobs(grpc::CallbackServerContext* context,
                                                const v1::ListJobsRequest* request,
                                                v1::ListJobsResponse* reply) {
  return unary(context, token_, [&] {
    for (v1::JobInfo& info : manager_.list(request->state())) *reply->add_jobs() = std::move(info);
  });
}

}  // namespace meshd
