#include "common/api/proto_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "google/protobuf/util/message_differencer.h"
#include "haptics/v1/scene.pb.h"
#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = (ScratchDir("proto_file") / name).string();
  std::ofstream(path) << text;
  return path;
}

// One scene written as text format and as JSON reads back as the same
// message; which parser is used follows the file name.
TEST(ProtoFileTest, TextAndJsonReadAlike) {
  pb::SceneSpec text, json;
  ASSERT_TRUE(ReadProtoFile(Write("scene.textproto", R"(name: "duo" step_s: 0.002
      objects { name: "a" kind: OBJECT_KIND_FIXED pose { position_m { z: -1 } } })"),
                            text)
                  .ok());
  ASSERT_TRUE(ReadProtoFile(Write("scene.json", R"({"name": "duo", "stepS": 0.002,
      "objects": [{"name": "a", "kind": "OBJECT_KIND_FIXED", "pose": {"positionM": {"z": -1}}}]})"),
                            json)
                  .ok());
  EXPECT_EQ(text.name(), "duo");
  EXPECT_EQ(text.objects(0).pose().position_m().z(), -1);
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(text, json));
  // JSON in a file not named .json is read as text format, and fails.
  pb::SceneSpec misnamed;
  EXPECT_EQ(ReadProtoFile(Write("scene.txt", R"({"name": "duo"})"), misnamed).code(),
            absl::StatusCode::kInvalidArgument);
}

// Text that does not parse is INVALID_ARGUMENT naming the file, the message
// type and the line of the first error.
TEST(ProtoFileTest, ParseErrorsNameFileTypeAndLine) {
  pb::SceneSpec spec;
  const std::string path = Write("bad.textproto", "name: \"x\"\nstep_s: 0.001\nnot_a_field: 3\n");
  const absl::Status status = ReadProtoFile(path, spec);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find(path), std::string::npos) << status;
  EXPECT_NE(status.message().find("SceneSpec"), std::string::npos) << status;
  EXPECT_NE(status.message().find("line 3"), std::string::npos) << status;
  const std::string json_path = Write("bad.json", "{\"name\": 3,");
  const absl::Status json = ReadProtoFile(json_path, spec);
  EXPECT_EQ(json.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(json.message().find(json_path), std::string::npos) << json;
  EXPECT_NE(json.message().find("in JSON"), std::string::npos) << json;
}

// A file that cannot be opened is NOT_FOUND.
TEST(ProtoFileTest, MissingFileIsNotFound) {
  pb::SceneSpec spec;
  EXPECT_EQ(
      ReadProtoFile((ScratchDir("proto_file_missing") / "none.textproto").string(), spec).code(),
      absl::StatusCode::kNotFound);
}

}  // namespace
}  // namespace hs
