#include "common/api/proto_file.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>
#include <google/protobuf/util/json_util.h>

#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

// Keeps the text parser's first error for the status instead of logging it.
class FirstError : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, int column, const std::string& message) override {
    if (text_.empty())
      text_ = absl::StrCat("line ", line + 1, ", column ", column + 1, ": ", message);
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

}  // namespace

absl::Status ReadProtoFile(const std::string& path, google::protobuf::Message& out) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat(path, ": cannot open"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string type = out.GetDescriptor()->name();
  if (path.ends_with(".json")) {
    const auto status = google::protobuf::util::JsonStringToMessage(text.str(), &out);
    if (!status.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat(path, ": not a ", type, " in JSON: ", status.message().as_string()));
    }
    return absl::OkStatus();
  }
  FirstError errors;
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(text.str(), &out)) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, ": not a ", type, " in text format: ", errors.text()));
  }
  return absl::OkStatus();
}

}  // namespace hs
