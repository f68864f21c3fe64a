// Requests parsed and replies serialized by the service itself instead of by gRPC's generated
// handlers. A request that protobuf cannot parse (random bytes, a tree nested past protobuf's
// recursion limit) then gets INVALID_ARGUMENT saying why; the generated handlers answer such a
// call with UNIMPLEMENTED and an empty message, as if the method did not exist.
#pragma once

#include <google/protobuf/message.h>
#include <grpcpp/support/byte_buffer.h>

namespace meshd {

// Parses `bytes` into `message`, or throws Error(kInvalidArgument, "request") naming the message
// type and why it could not be parsed.
void parse_message(const grpc::ByteBuffer& bytes, google::protobuf::Message& message);

template <typename Message>
Message parse_message(const grpc::ByteBuffer& bytes) {
  Message message;
  parse_message(bytes, message);
  return message;
}

// `message` in protobuf's wire format, as gRPC sends it.
grpc::ByteBuffer serialize_message(const google::protobuf::Message& message);

}  // namespace meshd
