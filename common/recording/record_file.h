#pragma once
// Recording files: a magic, then records, each as its length and CRC32C
// (both 4 bytes, little-endian) before the serialized haptics.v1.Record.
// A file cut short by a crash ends in a torn record: the reader stops at
// the last whole one and says where and why.

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "haptics/v1/recording.pb.h"

namespace hs {

/// The first bytes of every recording file.
inline constexpr char kRecordingMagic[] = "HSREC01\n";
inline constexpr size_t kRecordingMagicBytes = 8;
/// A record longer than this is taken for damage, not a record.
inline constexpr uint32_t kMaxRecordBytes = 64u << 20;

/// Appends records to a new file. Not thread-safe.
class RecordFileWriter {
 public:
  /// Creates `path` (which must not exist) and writes the magic.
  static absl::StatusOr<RecordFileWriter> Create(const std::string& path);
  RecordFileWriter(RecordFileWriter&& other) noexcept;
  /// Closes this file (without syncing it) and takes `other`'s.
  RecordFileWriter& operator=(RecordFileWriter&& other) noexcept;
  RecordFileWriter(const RecordFileWriter&) = delete;
  /// Closes the file (without syncing it).
  ~RecordFileWriter();

  /// Writes `record` in one write: a crash leaves it whole or torn, never
  /// interleaved with another.
  absl::Status Append(const haptics::v1::Record& record);
  /// Puts what was written on the disk (fdatasync).
  absl::Status Sync();

  const std::string& path() const { return path_; }
  /// Bytes in the file, magic included.
  int64_t bytes() const { return bytes_; }

 private:
  RecordFileWriter(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}

  std::string path_;
  int fd_ = -1;
  int64_t bytes_ = 0;
  std::string buffer_;  // one record's bytes, kept from record to record
};

/// What a recording file holds.
struct RecordFileContents {
  std::vector<haptics::v1::Record> records;
  /// Bytes of the file up to the end of the last whole record.
  int64_t whole_bytes = 0;
  /// Bytes of the file.
  int64_t file_bytes = 0;
  /// Why reading stopped before the end of the file ("" when it did not):
  /// a record cut short, a length out of range, a CRC32C that does not
  /// match, or bytes that do not parse as a Record.
  std::string torn_reason;
  bool torn() const { return !torn_reason.empty(); }
};

/// Reads every whole record of `path`. NOT_FOUND when it does not exist,
/// INVALID_ARGUMENT (naming it) when it does not start with the magic: not
/// a recording. A torn tail is no error: see RecordFileContents.
absl::StatusOr<RecordFileContents> ReadRecordFile(const std::string& path);

/// Cuts a torn tail off `path` (truncates it to its whole records and
/// syncs it); returns the bytes cut (0 for a whole file).
absl::StatusOr<int64_t> CutTornTail(const std::string& path);

}  // namespace hs
