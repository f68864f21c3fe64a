#include "server/wire_message.h"

#include <google/protobuf/io/coded_stream.h>
#include <grpcpp/impl/codegen/proto_utils.h>
#include <grpcpp/support/proto_buffer_reader.h>
#include <grpcpp/support/proto_buffer_writer.h>

#include <memory>
#include <string>

#include "core/common/error.h"

namespace meshd {

namespace {

// Protobuf's own default, which the generated handlers use too.
constexpr int kRecursionLimit = 100;
// Deep enough to tell "nested too deep" from "malformed" after a failed parse, shallow enough
// that the probe's recursion stays a fraction of a thread's stack.
constexpr int kDepthProbeLimit = 1000;

bool parse_within(const grpc::ByteBuffer& bytes, google::protobuf::Message& message, int depth) {
  grpc::ByteBuffer copy(bytes);  // the reader consumes its buffer; a copy shares the slices
  grpc::ProtoBufferReader reader(&copy);
  if (!reader.status().ok()) return false;
  google::protobuf::io::CodedInputStream input(&reader);
  input.SetRecursionLimit(depth);
  return message.ParseFromCodedStream(&input);
}

}  // namespace

void parse_message(const grpc::ByteBuffer& bytes, google::protobuf::Message& message) {
  if (parse_within(bytes, message, kRecursionLimit)) return;
  const std::string what = "could not be parsed as " + message.GetTypeName() + ": ";
  std::unique_ptr<google::protobuf::Message> probe(message.New());
  if (parse_within(bytes, *probe, kDepthProbeLimit)) {
    throw_invalid("request", what + "its messages nest more than " +
                                 std::to_string(kRecursionLimit) +
                                 " levels deep, protobuf's limit (each level of a shape tree is "
                                 "two of them)");
  }
  throw_invalid("request", what + "its " + std::to_string(bytes.Length()) +
                               " bytes are not protobuf's wire format of that message (a "
                               "truncated or malformed field, a field of the wrong type, or a "
                               "string that is not UTF-8)");
}

grpc::ByteBuffer serialize_message(const google::protobuf::Message& message) {
  grpc::ByteBuffer bytes;
  bool own_buffer = false;
  const grpc::Status status =
      grpc::GenericSerialize<grpc::ProtoBufferWriter, google::protobuf::Message>(message, &bytes,
                                                                                 &own_buffer);
  if (!status.ok()) {
    throw Error(ErrorCode::kInternal, "",
                "cannot serialize " + message.GetTypeName() + ": " + status.error_message());
  }
  return bytes;
}

}  // namespace meshd
