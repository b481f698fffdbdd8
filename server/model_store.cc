#include "server/model_store.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "common/sandbox/sandboxed_import.h"
#include "common/hash/sha256.h"
#include "server/state/durable_file.h"

namespace hs {
namespace {

bool IsIdText(const std::string& s, size_t max_size) {
  if (s.empty() || s.size() > max_size || s.front() == '.') return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

absl::Status ModelUpload::Add(const haptics::v1::UploadModelChunk& chunk) {
  if (chunk.has_header()) {
    if (has_header_) return absl::InvalidArgumentError("header repeated after the first chunk");
    const auto& h = chunk.header();
    if (!IsIdText(h.name(), 64)) {
      return absl::InvalidArgumentError("header.name: 1..64 of [A-Za-z0-9_.-], not starting '.'");
    }
    if (!IsIdText(h.format(), 8) || h.format().find('.') != std::string::npos) {
      return absl::InvalidArgumentError("header.format: a file extension such as 'stl'");
    }
    if (h.size_bytes() < 0) return absl::InvalidArgumentError("header.size_bytes: negative");
    if (h.size_bytes() > max_bytes_) {
      return absl::ResourceExhaustedError(
          absl::StrCat("model of ", h.size_bytes(), " bytes is over the limit of ", max_bytes_));
    }
    if (h.sha256().size() != 32) return absl::InvalidArgumentError("header.sha256: not 32 bytes");
    header_ = h;
    has_header_ = true;
  } else if (!has_header_) {
    return absl::InvalidArgumentError("the first chunk must carry the header");
  }
  if (static_cast<int64_t>(data_.size() + chunk.data().size()) > header_.size_bytes()) {
    return absl::InvalidArgumentError("more bytes than header.size_bytes");
  }
  data_ += chunk.data();
  return absl::OkStatus();
}

absl::Status ModelUpload::Verify() const {
  if (!has_header_) return absl::InvalidArgumentError("no header");
  if (static_cast<int64_t>(data_.size()) != header_.size_bytes()) {
    return absl::InvalidArgumentError(
        absl::StrCat("got ", data_.size(), " bytes, header.size_bytes is ", header_.size_bytes()));
  }
  if (Sha256Of(data_) != header_.sha256()) {
    return absl::InvalidArgumentError("sha256 does not match the data");
  }
  return absl::OkStatus();
}

ModelStore::ModelStore(std::string dir, int max_models)
    : dir_(std::move(dir)), max_models_(max_models) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir_, error)) {
    const std::string id = entry.path().filename().string();
    if (!entry.is_regular_file()) continue;
    if (id.starts_with(".")) {  // an upload a crash cut short
      std::filesystem::remove(entry.path(), error);
      continue;
    }
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    sha256_by_id_[id] = Sha256Of(bytes.str());
  }
}

absl::StatusOr<StoredModel> ModelStore::Store(const ModelUpload& upload) {
  if (absl::Status s = upload.Verify(); !s.ok()) return s;
  const std::string id = absl::StrCat(upload.header().name(), ".", upload.header().format());
  std::lock_guard lock(mu_);
  const std::filesystem::path kept = std::filesystem::path(dir_) / id;
  if (const auto it = sha256_by_id_.find(id); it != sha256_by_id_.end()) {
    if (it->second != upload.header().sha256()) {
      return absl::AlreadyExistsError(
          absl::StrCat("model '", id, "' exists with other content; delete it first"));
    }
    // The same bytes again: the stored model, counted afresh.
    absl::StatusOr<ImportedModel> model = SandboxedImport(kept.string(), ImportOptions{});
    if (!model.ok()) return absl::InternalError(absl::StrCat("model '", id, "' no longer imports"));
    return StoredModel{id, model->object.num_vertices(), model->object.num_faces(), true};
  }
  if (static_cast<int>(sha256_by_id_.size()) >= max_models_) {
    return absl::ResourceExhaustedError(absl::StrCat("at most ", max_models_, " models"));
  }
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  // Written under a hidden name first, whole and on the disk: BuildScene
  // never sees a model that failed to import, and a crash leaves a hidden
  // file that the next start removes.
  const std::filesystem::path staged = std::filesystem::path(dir_) / ("." + id);
  if (absl::Status s = WriteFileDurably(staged.string(), upload.data()); !s.ok()) {
    return absl::InternalError(s.message());
  }
  absl::StatusOr<ImportedModel> model = SandboxedImport(staged.string(), ImportOptions{});
  if (!model.ok()) {
    std::filesystem::remove(staged, error);
    return absl::InvalidArgumentError(
        absl::StrCat("model '", id, "' does not import: ", model.status().message()));
  }
  std::filesystem::rename(staged, kept, error);
  if (error) {
    std::filesystem::remove(staged, error);
    return absl::InternalError(absl::StrCat("cannot keep model: ", error.message()));
  }
  // Acknowledged only once the rename is on the disk too.
  if (absl::Status s = SyncFolder(dir_); !s.ok()) return absl::InternalError(s.message());
  sha256_by_id_[id] = upload.header().sha256();
  return StoredModel{id, model->object.num_vertices(), model->object.num_faces()};
}

bool ModelStore::Has(const std::string& id) const {
  std::lock_guard lock(mu_);
  return sha256_by_id_.count(id) > 0;
}

absl::Status ModelStore::Delete(const std::string& id) {
  std::lock_guard lock(mu_);
  if (sha256_by_id_.erase(id) == 0) return absl::NotFoundError(absl::StrCat("no model '", id, "'"));
  std::error_code error;
  std::filesystem::remove(std::filesystem::path(dir_) / id, error);
  return absl::OkStatus();
}

}  // namespace hs
