#pragma once
// Reading a haptics.v1 message from a file a person wrote: JSON when the
// name ends in ".json", protobuf text format otherwise (scene files,
// exercise files).

#include <google/protobuf/message.h>

#include <string>

#include "absl/status/status.h"

namespace hs {

/// Fills `out`. NOT_FOUND when the file cannot be opened; INVALID_ARGUMENT
/// naming the file, the message type and the first error's line when it
/// does not parse.
absl::Status ReadProtoFile(const std::string& path, google::protobuf::Message& out);

}  // namespace hs
