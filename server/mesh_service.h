// meshd.v1.MeshService on gRPC's callback API: thin handlers that check the token, convert, call
// the JobManager and stream. They never mesh.
#pragma once

#include "meshd/v1/service.grpc.pb.h"
#include "server/bearer_token.h"
#include "server/job_manager.h"
#include "server/metrics.h"

namespace meshd {

class MeshService final : public v1::MeshService::CallbackService {
 public:
  MeshService(JobManager& manager, Metrics& metrics, BearerToken token)
      : manager_(manager), metrics_(metrics), token_(std::move(token)) {}

  grpc::ServerWriteReactor<v1::MeshEvent>* Generate(grpc::CallbackServerContext* context,
                                                    const v1::MeshRequest* request) override;
  grpc::ServerUnaryReactor* Submit(grpc::CallbackServerContext* context,
                                   const v1::MeshRequest* request, v1::JobRef* reply) override;
  grpc::ServerWriteReactor<v1::MeshEvent>* Watch(grpc::CallbackServerContext* context,
                                                 const v1::JobRef* request) override;
  grpc::ServerUnaryReactor* Cancel(grpc::CallbackServerContext* context, const v1::JobRef* request,
                                   v1::JobInfo* reply) override;
  grpc::ServerUnaryReactor* GetJob(grpc::CallbackServerContext* context, const v1::JobRef* request,
                                   v1::JobInfo* reply) override;
  grpc::ServerUnaryReactor* ListJobs(grpc::CallbackServerContext* context,
                                     const v1::ListJobsRequest* request,
                                     v1::ListJobsResponse* reply) override;

 private:
  JobManager& manager_;
  Metrics& metrics_;
  const BearerToken token_;
};

}  // namespace meshd
