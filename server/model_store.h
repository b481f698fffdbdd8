#pragma once
// Uploaded models: assembled from chunks, checked against their SHA-256,
// imported once to reject malformed meshes, then kept in one folder by
// their content's SHA-256, each model id a link where BuildScene finds it.

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

/// The folder of uploaded models, content-addressed: each distinct
/// content is one file named by its SHA-256, "<hex>.<format>", and each
/// model id ("<name>.<format>", where BuildScene looks) is a symbolic link
/// to its content. Every write is durable before it is acknowledged
/// (temporary name, fsync, rename, fsync of the folder). Thread-safe.
class ModelStore {
 public:
  /// Keeps models in `dir` (created if missing), at most `max_models`.
  /// Load() reads what the folder holds.
  ModelStore(std::string dir, int max_models);

  /// Takes the models already in the folder (a --state-dir kept across
  /// restarts): they count and keep their ids. Removes what a crash left
  /// of an upload that was never acknowledged; moves a model file named by
  /// its id (the folder's earlier layout) to its content's name.
  /// FAILED_PRECONDITION naming the file when a model's content is missing
  /// or does not match its SHA-256: no start on half a store.
  absl::Status Load();

  /// Imports a verified upload (in the import sandbox) and keeps it. The
  /// same bytes under a stored id return that model; other bytes under it
  /// are ALREADY_EXISTS. INVALID_ARGUMENT when the file does not import as
  /// a mesh, RESOURCE_EXHAUSTED past max_models; nothing is kept on error.
  absl::StatusOr<StoredModel> Store(const ModelUpload& upload);
  /// Whether model `id` is stored.
  bool Has(const std::string& id) const;
  /// Deletes model `id` (and its content, unless another id shares it).
  /// NOT_FOUND when there is none.
  absl::Status Delete(const std::string& id);

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  int max_models_;
  mutable std::mutex mu_;
  std::map<std::string, std::string> sha256_by_id_;  // guarded by mu_
};

}  // namespace hs
