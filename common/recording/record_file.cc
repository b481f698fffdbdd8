#include "common/recording/record_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "common/hash/crc32c.h"

namespace hs {
namespace {

absl::Status ErrnoError(const std::string& what, const std::string& path) {
  return absl::InternalError(absl::StrCat(what, " ", path, ": ", std::strerror(errno)));
}

void PutUint32(uint32_t v, char* out) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((v >> (8 * i)) & 0xFF);
}

uint32_t GetUint32(const char* in) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t{static_cast<uint8_t>(in[i])} << (8 * i);
  return v;
}

// Writes all of `bytes`, resuming after short writes and signals.
bool WriteAll(int fd, const char* bytes, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

absl::StatusOr<RecordFileWriter> RecordFileWriter::Create(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return ErrnoError("cannot create", path);
  RecordFileWriter writer(path, fd);
  if (!WriteAll(fd, kRecordingMagic, kRecordingMagicBytes)) return ErrnoError("cannot write", path);
  writer.bytes_ = kRecordingMagicBytes;
  return writer;
}

RecordFileWriter::RecordFileWriter(RecordFileWriter&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      bytes_(other.bytes_),
      buffer_(std::move(other.buffer_)) {}

RecordFileWriter& RecordFileWriter::operator=(RecordFileWriter&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    bytes_ = other.bytes_;
    buffer_ = std::move(other.buffer_);
  }
  return *this;
}

RecordFileWriter::~RecordFileWriter() {
  if (fd_ >= 0) ::close(fd_);
}

absl::Status RecordFileWriter::Append(const haptics::v1::Record& record) {
  const size_t size = record.ByteSizeLong();
  if (size > kMaxRecordBytes) {
    return absl::InvalidArgumentError(absl::StrCat("a record of ", size, " bytes is too long"));
  }
  buffer_.resize(8 + size);
  record.SerializeWithCachedSizesToArray(reinterpret_cast<uint8_t*>(buffer_.data() + 8));
  PutUint32(static_cast<uint32_t>(size), buffer_.data());
  PutUint32(Crc32c(std::string_view(buffer_).substr(8)), buffer_.data() + 4);
  if (!WriteAll(fd_, buffer_.data(), buffer_.size())) return ErrnoError("cannot write", path_);
  bytes_ += static_cast<int64_t>(buffer_.size());
  return absl::OkStatus();
}

absl::Status RecordFileWriter::Sync() {
  if (::fdatasync(fd_) != 0) return ErrnoError("cannot sync", path_);
  return absl::OkStatus();
}

absl::StatusOr<RecordFileContents> ReadRecordFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::NotFoundError(absl::StrCat("no recording file ", path));
  std::ostringstream all;
  all << in.rdbuf();
  const std::string bytes = all.str();
  if (bytes.size() < kRecordingMagicBytes ||
      bytes.compare(0, kRecordingMagicBytes, kRecordingMagic) != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, " is not a recording (it does not start with the recording magic)"));
  }
  RecordFileContents contents;
  contents.file_bytes = static_cast<int64_t>(bytes.size());
  size_t at = kRecordingMagicBytes;
  while (at < bytes.size()) {
    if (bytes.size() - at < 8) {
      contents.torn_reason = "a record header cut short";
      break;
    }
    const uint32_t size = GetUint32(bytes.data() + at);
    const uint32_t crc = GetUint32(bytes.data() + at + 4);
    if (size > kMaxRecordBytes) {
      contents.torn_reason = absl::StrCat("a record length of ", size, " bytes");
      break;
    }
    if (bytes.size() - at - 8 < size) {
      contents.torn_reason = "a record cut short";
      break;
    }
    const std::string_view payload(bytes.data() + at + 8, size);
    if (Crc32c(payload) != crc) {
      contents.torn_reason = "a record whose CRC32C does not match";
      break;
    }
    haptics::v1::Record record;
    if (!record.ParseFromArray(payload.data(), static_cast<int>(payload.size()))) {
      contents.torn_reason = "a record that does not parse";
      break;
    }
    contents.records.push_back(std::move(record));
    at += 8 + size;
  }
  contents.whole_bytes = static_cast<int64_t>(at);
  return contents;
}

absl::StatusOr<int64_t> CutTornTail(const std::string& path) {
  absl::StatusOr<RecordFileContents> contents = ReadRecordFile(path);
  if (!contents.ok()) return contents.status();
  const int64_t cut = contents->file_bytes - contents->whole_bytes;
  if (cut == 0) return 0;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return ErrnoError("cannot open", path);
  const bool ok = ::ftruncate(fd, contents->whole_bytes) == 0 && ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) return ErrnoError("cannot cut", path);
  return cut;
}

}  // namespace hs
