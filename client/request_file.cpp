#include "client/request_file.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

#include "core/common/error.h"

namespace meshd {
namespace {

// Keeps the parser's messages as "source:line:column: message", counting from 1 as editors do.
class CollectErrors : public google::protobuf::io::ErrorCollector {
 public:
  explicit CollectErrors(const std::string& source) : source_(source) {}

  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (!errors_.empty()) errors_ += "; ";
    errors_ += source_ + ":" + std::to_string(line + 1) + ":" + std::to_string(column + 1) + ": " +
               message;
  }

  const std::string& errors() const { return errors_; }

 private:
  const std::string& source_;
  std::string errors_;
};

}  // namespace

v1::MeshRequest parse_request_text(const std::string& text, const std::string& source) {
  v1::MeshRequest request;
  CollectErrors errors(source);
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(text, &request)) {
    throw_invalid("request", errors.errors().empty()
                                 ? source + ": not a valid meshd.v1.MeshRequest in text format"
                                 : errors.errors());
  }
  return request;
}

v1::MeshRequest read_request_file(const std::string& path) {
  // A directory opens like a file and then reads as empty; say what it is instead.
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw_invalid("request", "cannot read '" + path + "': it is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_invalid("request", "cannot open '" + path + "': " + std::strerror(errno));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw_invalid("request", "cannot read '" + path + "': " + std::strerror(errno));
  return parse_request_text(text, path);
}

}  // namespace meshd
