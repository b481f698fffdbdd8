#include "common/recording/session_reader.h"

#include "absl/strings/str_cat.h"
#include "common/recording/record_file.h"
#include "common/recording/session_files.h"

namespace hs {

absl::StatusOr<RecordedSession> ReadSession(const std::string& file) {
  RecordedSession session;
  for (const std::string& path : SessionParts(file)) {
    absl::StatusOr<RecordFileContents> contents = ReadRecordFile(path);
    if (!contents.ok()) return contents.status();
    if (contents->records.empty() || !contents->records.front().has_start()) {
      if (!session.files.empty()) break;  // a part a crash cut before its start: none follows
      return absl::InvalidArgumentError(
          absl::StrCat(path, ": no session start at its beginning (",
                       contents->torn() ? contents->torn_reason : "an empty recording", ")"));
    }
    const int part = contents->records.front().start().part();
    if (!session.files.empty() && part != session.files.back().part + 1) {
      return absl::InvalidArgumentError(
          absl::StrCat(path, ": part ", part, " after part ", session.files.back().part));
    }
    session.files.push_back({.path = path,
                             .part = part,
                             .bytes = contents->file_bytes,
                             .whole_bytes = contents->whole_bytes,
                             .torn_reason = contents->torn_reason});
    for (haptics::v1::Record& record : contents->records) {
      session.records.push_back(std::move(record));
    }
    if (contents->torn()) break;
  }
  return session;
}

}  // namespace hs
