#pragma once
// Uploaded models: assembled from chunks, checked against their SHA-256,
// imported once to reject malformed meshes, then kept as files in one
// folder, named by their model id, where BuildScene finds them.

#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "absl/status/statusor.h"
#include "haptics/v1/scene_service.pb.h"

namespace hs {

/// What an accepted upload became.
struct StoredModel {
  /// "<name>.<format>": the file name in the store, and the id scenes use.
  std::string model_id;
  int32_t vertices = 0;
  int32_t triangles = 0;
  /// Stored before, from the same bytes (nothing new was kept).
  bool existed = false;
};

/// One upload in progress (one per UploadModel stream; not thread-safe).
class ModelUpload {
 public:
  /// At most `max_bytes` of model data.
  explicit ModelUpload(int64_t max_bytes) : max_bytes_(max_bytes) {}

  /// Adds a chunk: the first must carry the header, later ones must not.
  /// INVALID_ARGUMENT for a missing or repeated header, a bad name or
  /// format, or more bytes than announced; RESOURCE_EXHAUSTED past
  /// max_bytes.
  absl::Status Add(const haptics::v1::UploadModelChunk& chunk);

  /// INVALID_ARGUMENT when no header came, the size differs from the
  /// header's, or the SHA-256 does not match.
  absl::Status Verify() const;

  const haptics::v1::UploadModelChunk::Header& header() const { return header_; }
  const std::string& data() const { return data_; }

 private:
  int64_t max_bytes_;
  bool has_header_ = false;
  haptics::v1::UploadModelChunk::Header header_;
  std::string data_;
};

/// The folder of uploaded models. Thread-safe.
class ModelStore {
 public:
  /// Keeps models in `dir` (created if missing), at most `max_models`;
  /// the models already in `dir` (a --model-dir kept across restarts)
  /// count and keep their ids.
  ModelStore(std::string dir, int max_models);

  /// Imports a verified upload (in the import sandbox) and keeps it. The
  /// same bytes under a stored id return that model; other bytes under it
  /// are ALREADY_EXISTS. INVALID_ARGUMENT when the file does not import as
  /// a mesh, RESOURCE_EXHAUSTED past max_models; nothing is kept on error.
  absl::StatusOr<StoredModel> Store(const ModelUpload& upload);
  /// Whether model `id` is stored.
  bool Has(const std::string& id) const;
  /// Deletes model `id`. NOT_FOUND when there is none.
  absl::Status Delete(const std::string& id);

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  int max_models_;
  mutable std::mutex mu_;
  std::map<std::string, std::string> sha256_by_id_;  // guarded by mu_
};

}  // namespace hs
