// The optional shared-secret check: every meshd.v1 call must carry the metadata
// "authorization: Bearer <token>". The health service stays open for probes.
#pragma once

#include <grpcpp/grpcpp.h>

#include <string>

namespace meshd {

class BearerToken {
 public:
  // An empty token turns the check off.
  explicit BearerToken(std::string token) : token_(std::move(token)) {}

  // OK, or UNAUTHENTICATED saying what was wrong (never echoing a token).
  grpc::Status check(const grpc::CallbackServerContext& context) const;

 private:
  std::string token_;
};

}  // namespace meshd
