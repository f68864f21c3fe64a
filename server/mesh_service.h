// meshd.v1.MeshService on gRPC's callback API: thin handlers that check the token, parse,
// convert, call the JobManager and stream. They never mesh. Every method is registered raw (bytes
// in, bytes out) so that the service parses requests itself: one that protobuf cannot parse gets
// INVALID_ARGUMENT saying why (server/wire_message.h).
#pragma once

#include "meshd/v1/service.grpc.pb.h"
#include "server/bearer_token.h"
#include "server/job_manager.h"
#include "server/metrics.h"

namespace meshd {

using RawMeshService = v1::MeshService::WithRawCallbackMethod_Generate<
    v1::MeshService::WithRawCallbackMethod_Submit<v1::MeshService::WithRawCallbackMethod_Watch<
        v1::MeshService::WithRawCallbackMethod_Cancel<v1::MeshService::WithRawCallbackMethod_GetJob<
            v1::MeshService::WithRawCallbackMethod_ListJobs<v1::MeshService::Service>>>>>>;

// Each method's bytes are the message its proto names: MeshRequest in, MeshEvent stream out for
// Generate, and so on.
class MeshService final : public RawMeshService {
 public:
  MeshService(JobManager& manager, Metrics& metrics, BearerToken token)
      : manager_(manager), metrics_(metrics), token_(std::move(token)) {}

  grpc::ServerWriteReactor<grpc::ByteBuffer>* Generate(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* request) override;
  grpc::ServerUnaryReactor* Submit(grpc::CallbackServerContext* context,
                                   const grpc::ByteBuffer* request,
                                   grpc::ByteBuffer* reply) override;
  grpc::ServerWriteReactor<grpc::ByteBuffer>* Watch(grpc::CallbackServerContext* context,
                                                    const grpc::ByteBuffer* request) override;
  grpc::ServerUnaryReactor* Cancel(grpc::CallbackServerContext* context,
                                   const grpc::ByteBuffer* request,
                                   grpc::ByteBuffer* reply) override;
  grpc::ServerUnaryReactor* GetJob(grpc::CallbackServerContext* context,
                                   const grpc::ByteBuffer* request,
                                   grpc::ByteBuffer* reply) override;
  grpc::ServerUnaryReactor* ListJobs(grpc::CallbackServerContext* context,
                                     const grpc::ByteBuffer* request,
                                     grpc::ByteBuffer* reply) override;

 private:
  JobManager& manager_;
  Metrics& metrics_;
  const BearerToken token_;
};

}  // namespace meshd
