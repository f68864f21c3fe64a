#include "client/commands.h"

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/json_util.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <variant>

#include "client/event_view.h"
#include "client/exit_codes.h"
#include "client/frame_writer.h"
#include "client/result_assembly.h"
#include "client/simple_request.h"
#include "core/common/error.h"
#include "core/mesh/mesh_file.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "meshd/v1/service.grpc.pb.h"

namespace meshd::cli {

namespace {

// Reports a failed call: the status name and the server's message, which starts with the
// field path for a bad request. JSON mode prints it as an object too.
int report(const grpc::Status& status, bool json, EventView* view = nullptr) {
  if (view != nullptr) view->end_line();
  std::fprintf(stderr, "meshctl: %s: %s\n", status_code_name(status.error_code()),
               status.error_message().c_str());
  if (json) {
    std::printf("{\"status\":\"%s\",\"code\":%d,\"message\":%s}\n",
                status_code_name(status.error_code()), static_cast<int>(status.error_code()),
                [&] {
                  std::string s = "\"";
                  for (char c : status.error_message()) {
                    if (c == '"' || c == '\\') s += '\\';
                    if (static_cast<unsigned char>(c) < 0x20) continue;
                    s += c;
                  }
                  return s + "\"";
                }()
                    .c_str());
  }
  return exit_code_for(status.error_code());
}

int report_error(const Error& e) {
  std::fprintf(stderr, "meshctl: %s\n", e.what());
  // A meshctl without GDAL asked for a raster or an import is a failed precondition, not a bad
  // result.
  if (e.code() == ErrorCode::kFailedPrecondition) return kExitFailedPrecondition;
  return e.code() == ErrorCode::kInvalidArgument ? kExitBadRequest : kExitBadResult;
}

void write_outputs(const std::variant<Mesh, TetMesh>& mesh, const CliOptions& o) {
  for (const std::string& path : o.outputs) {
    const MeshFormat format =
        o.format.empty() ? format_from_path(path, "-o") : parse_format_name(o.format, "--format");
    std::visit([&](const auto& m) { write_mesh_file(m, path, format); }, mesh);
    if (!o.json) std::printf("wrote %s (%s)\n", path.c_str(), format_name(format));
  }
}

// Reads a Generate or Watch stream to its end: shows events, writes frames, and at done
// checks the result and writes the outputs.
int follow(grpc::ClientReaderInterface<v1::MeshEvent>& reader, const CliOptions& o) {
  EventView view(EventView::mode_for(o.json));
  std::unique_ptr<FrameWriter> frames;
  if (!o.frames_dir.empty()) frames = std::make_unique<FrameWriter>(o.frames_dir);
  ResultAssembly assembly;
  v1::MeshEvent event;
  int code = kExitOk;
  while (reader.Read(&event)) {
    view.show(event);
    try {
      if (event.has_snapshot() && frames) frames->write(event.snapshot());
      if (event.has_result_chunk()) assembly.add(event.result_chunk());
      if (event.has_done()) {
        const std::variant<Mesh, TetMesh> mesh = assembly.finish(event.done());
        view.summary(event.done(), event.job_id());
        write_outputs(mesh, o);
        if (frames && !o.json)
          std::printf("wrote %d frames to %s\n", frames->frames(), o.frames_dir.c_str());
      }
    } catch (const Error& e) {
      // What fails here is the result, a frame or an output file, never the request (an -o
      // whose path cannot be created throws kInvalidArgument): exit 11, not 2.
      view.end_line();
      std::fprintf(stderr, "meshctl: %s\n", e.what());
      code = kExitBadResult;
    }
  }
  const grpc::Status status = reader.Finish();
  if (!status.ok()) return report(status, o.json, &view);
  return code;
}

// build_request, with what an import brought in said on stderr (stdout stays the events').
v1::MeshRequest checked_request(const CliOptions& o) {
  std::string import_summary;
  v1::MeshRequest request = build_request(o, &import_summary);
  if (!import_summary.empty()) std::fprintf(stderr, "meshctl: %s\n", import_summary.c_str());
  return request;
}

// meshctl request: the request generate would send, in text format, to -o FILE or stdout, so
// that an import or the shape flags can be kept, edited and rerun (by meshctl or meshbench).
int write_request(const CliOptions& o) {
  if (o.outputs.size() > 1)
    throw_invalid("-o", "request writes one file (got " + std::to_string(o.outputs.size()) + ")");
  std::string text =
      "# proto-file: meshd/v1/request.proto\n# proto-message: meshd.v1.MeshRequest\n";
  std::string body;
  google::protobuf::TextFormat::PrintToString(checked_request(o), &body);
  text += body;
  if (o.outputs.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return kExitOk;
  }
  std::ofstream out(o.outputs[0], std::ios::binary);
  if (!(out << text) || !out.flush()) {
    std::fprintf(stderr, "meshctl: -o: cannot write '%s': %s\n", o.outputs[0].c_str(),
                 std::strerror(errno));
    return kExitBadResult;
  }
  return kExitOk;
}

v1::JobRef job_ref(const CliOptions& o) {
  if (o.args.size() != 1) throw_invalid("JOB_ID", "give one job id");
  v1::JobRef ref;
  ref.set_job_id(o.args[0]);
  return ref;
}

void print_job(const v1::JobInfo& info, bool json) {
  if (json) {
    std::string out;
    google::protobuf::util::JsonPrintOptions options;
    options.preserve_proto_field_names = true;
    (void)google::protobuf::util::MessageToJsonString(info, &out, options);
    std::printf("%s\n", out.c_str());
    return;
  }
  std::string state = v1::JobState_Name(info.state());
  state = state.substr(std::string("JOB_STATE_").size());
  std::printf("%s  %-9s", info.job_id().c_str(), state.c_str());
  if (info.state() == v1::JOB_STATE_QUEUED) std::printf("  position %d", info.queue_position());
  if (!info.device().empty()) std::printf("  on %s", info.device().c_str());
  if (info.iteration() > 0) std::printf("  iteration %d", info.iteration());
  if (info.nodes() > 0) std::printf("  %lld nodes", static_cast<long long>(info.nodes()));
  if (info.run_s() > 0) std::printf("  %.3f s", info.run_s());
  if (info.has_done()) {
    std::printf("  q_min %.3f q_mean %.4f", info.done().quality().q_min(),
                info.done().quality().q_mean());
  }
  if (!info.label().empty()) std::printf("  [%s]", info.label().c_str());
  if (!info.error_message().empty()) std::printf("  (%s)", info.error_message().c_str());
  std::printf("\n");
}

int health(const Connection& connection, bool json) {
  auto stub = grpc::health::v1::Health::NewStub(connection.channel());
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  auto context = connection.context();
  const grpc::Status status = stub->Check(context.get(), request, &response);
  if (!status.ok()) return report(status, json);
  const std::string name =
      grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status());
  if (json)
    std::printf("{\"status\":\"%s\"}\n", name.c_str());
  else
    std::printf("%s\n", name.c_str());
  return response.status() == grpc::health::v1::HealthCheckResponse::SERVING ? kExitOk
                                                                             : kExitNotServing;
}

}  // namespace

int run_command(const CliOptions& o) {
  try {
    if (o.command == "request") return write_request(o);
    const Connection connection(o.connection);
    auto stub = v1::MeshService::NewStub(connection.channel());
    auto context = connection.context();
    if (o.command == "health") return health(connection, o.json);
    if (o.command == "generate") {
      const v1::MeshRequest request = checked_request(o);
      for (const auto& path : o.outputs) {  // a bad -o fails before the job, not after
        if (o.format.empty()) format_from_path(path, "-o");
      }
      if (!o.format.empty()) parse_format_name(o.format, "--format");
      auto reader = stub->Generate(context.get(), request);
      return follow(*reader, o);
    }
    if (o.command == "submit") {
      v1::JobRef ref;
      const grpc::Status status = stub->Submit(context.get(), checked_request(o), &ref);
      if (!status.ok()) return report(status, o.json);
      if (o.json)
        std::printf("{\"job_id\":\"%s\"}\n", ref.job_id().c_str());
      else
        std::printf("%s\n", ref.job_id().c_str());
      return kExitOk;
    }
    if (o.command == "watch") {
      auto reader = stub->Watch(context.get(), job_ref(o));
      return follow(*reader, o);
    }
    if (o.command == "cancel" || o.command == "status") {
      v1::JobInfo info;
      const grpc::Status status = o.command == "cancel"
                                      ? stub->Cancel(context.get(), job_ref(o), &info)
                                      : stub->GetJob(context.get(), job_ref(o), &info);
      if (!status.ok()) return report(status, o.json);
      print_job(info, o.json);
      return kExitOk;
    }
    if (o.command == "list") {
      v1::ListJobsRequest request;
      if (!o.state.empty()) {
        v1::JobState state;
        std::string name = "JOB_STATE_" + o.state;
        for (auto& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (!v1::JobState_Parse(name, &state)) {
          throw_invalid(
              "--state",
              "must be queued, running, succeeded, failed or cancelled (got '" + o.state + "')");
        }
        request.set_state(state);
      }
      v1::ListJobsResponse response;
      const grpc::Status status = stub->ListJobs(context.get(), request, &response);
      if (!status.ok()) return report(status, o.json);
      for (const auto& info : response.jobs()) print_job(info, o.json);
      return kExitOk;
    }
    throw_invalid(o.command, "unknown command");
  } catch (const Error& e) {
    return report_error(e);
  }
}

}  // namespace meshd::cli
