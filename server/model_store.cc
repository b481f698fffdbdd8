#include "server/model_store.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "common/hash/sha256.h"
#include "common/sandbox/sandboxed_import.h"
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

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The content file of bytes with digest `sha256` of model `id`: the hex
// digest and the id's format ("<hex>.<format>").
std::string ContentName(const std::string& sha256, const std::string& id) {
  return absl::StrCat(absl::BytesToHexString(sha256),
                      std::filesystem::path(id).extension().string());
}

// Whether `name` is a content file's: 64 hex digits, a dot, a format.
bool IsContentName(const std::string& name) {
  if (name.size() < 66 || name[64] != '.') return false;
  return std::all_of(name.begin(), name.begin() + 64,
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// Makes `dir`/`id` a link to `target` (a name in `dir`): made under a
// hidden name, renamed over, the folder synced.
std::error_code LinkDurably(const std::string& dir, const std::string& id,
                            const std::string& target) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path staged = fs::path(dir) / ("." + id + ".link");
  fs::remove(staged, error);
  fs::create_symlink(target, staged, error);
  if (!error) fs::rename(staged, fs::path(dir) / id, error);
  if (error) {
    std::error_code ignored;
    fs::remove(staged, ignored);
    return error;
  }
  if (!SyncFolder(dir).ok()) return std::make_error_code(std::errc::io_error);
  return {};
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
    : dir_(std::move(dir)), max_models_(max_models) {}

absl::Status ModelStore::Load() {
  namespace fs = std::filesystem;
  std::error_code error;
  std::map<std::string, std::string> sha256_by_id;
  std::set<std::string> linked;  // content files some id points at
  std::vector<fs::path> contents, legacy;
  for (const auto& entry : fs::directory_iterator(dir_, error)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(".")) {  // an upload a crash cut short
      fs::remove(entry.path(), error);
    } else if (entry.is_symlink()) {
      const fs::path target = fs::read_symlink(entry.path(), error);
      const fs::path content = fs::path(dir_) / target;
      const std::string hex = target.stem().string();
      if (!fs::is_regular_file(content, error)) {
        return absl::FailedPreconditionError(absl::StrCat("model '", name, "' (",
                                                          entry.path().string(), "): its content ",
                                                          content.string(), " is missing"));
      }
      if (absl::BytesToHexString(Sha256Of(ReadAll(content))) != hex) {
        return absl::FailedPreconditionError(
            absl::StrCat("model '", name, "': ", content.string(), " does not match its SHA-256"));
      }
      sha256_by_id[name] = absl::HexStringToBytes(hex);
      linked.insert(target.string());
    } else if (entry.is_regular_file()) {
      (IsContentName(name) ? contents : legacy).push_back(entry.path());
    }
  }
  // Content no id points at: an upload cut between its content and its id.
  for (const fs::path& content : contents) {
    if (!linked.count(content.filename().string())) fs::remove(content, error);
  }
  std::lock_guard lock(mu_);
  sha256_by_id_ = std::move(sha256_by_id);
  for (const fs::path& file : legacy) {  // named by id: the earlier layout
    const std::string id = file.filename().string();
    const std::string sha256 = Sha256Of(ReadAll(file));
    const fs::path content = fs::path(dir_) / ContentName(sha256, id);
    if (!fs::exists(content, error)) fs::rename(file, content, error);
    if (!error) error = LinkDurably(dir_, id, content.filename().string());
    if (error) {
      return absl::FailedPreconditionError(absl::StrCat("cannot move model ", file.string(), " to ",
                                                        content.string(), ": ", error.message()));
    }
    sha256_by_id_[id] = sha256;
  }
  return absl::OkStatus();
}

absl::StatusOr<StoredModel> ModelStore::Store(const ModelUpload& upload) {
  namespace fs = std::filesystem;
  if (absl::Status s = upload.Verify(); !s.ok()) return s;
  const std::string id = absl::StrCat(upload.header().name(), ".", upload.header().format());
  const std::string sha256 = upload.header().sha256();
  std::lock_guard lock(mu_);
  const fs::path content = fs::path(dir_) / ContentName(sha256, id);
  if (const auto it = sha256_by_id_.find(id); it != sha256_by_id_.end()) {
    if (it->second != sha256) {
      return absl::AlreadyExistsError(
          absl::StrCat("model '", id, "' exists with other content; delete it first"));
    }
    // The same bytes again: the stored model, counted afresh.
    absl::StatusOr<ImportedModel> model = SandboxedImport(content.string(), ImportOptions{});
    if (!model.ok()) return absl::InternalError(absl::StrCat("model '", id, "' no longer imports"));
    return StoredModel{id, model->object.num_vertices(), model->object.num_faces(), true};
  }
  if (static_cast<int>(sha256_by_id_.size()) >= max_models_) {
    return absl::ResourceExhaustedError(absl::StrCat("at most ", max_models_, " models"));
  }
  std::error_code error;
  fs::create_directories(dir_, error);
  // Written under a hidden name first, whole and on the disk: BuildScene
  // never sees a model that failed to import, and a crash leaves a hidden
  // file that the next start removes.
  const fs::path staged = fs::path(dir_) / ("." + content.filename().string());
  if (absl::Status s = WriteFileDurably(staged.string(), upload.data()); !s.ok()) {
    return absl::InternalError(s.message());
  }
  absl::StatusOr<ImportedModel> model = SandboxedImport(staged.string(), ImportOptions{});
  if (!model.ok()) {
    fs::remove(staged, error);
    return absl::InvalidArgumentError(
        absl::StrCat("model '", id, "' does not import: ", model.status().message()));
  }
  // Content another id has already: kept once.
  if (fs::exists(content, error)) {
    fs::remove(staged, error);
  } else {
    fs::rename(staged, content, error);
  }
  // Acknowledged only once the content's name and the id are on the disk.
  if (!error) error = LinkDurably(dir_, id, content.filename().string());
  if (error) {
    fs::remove(staged, error);
    return absl::InternalError(absl::StrCat("cannot keep model '", id, "': ", error.message()));
  }
  sha256_by_id_[id] = sha256;
  return StoredModel{id, model->object.num_vertices(), model->object.num_faces()};
}

bool ModelStore::Has(const std::string& id) const {
  std::lock_guard lock(mu_);
  return sha256_by_id_.count(id) > 0;
}

absl::Status ModelStore::Delete(const std::string& id) {
  std::lock_guard lock(mu_);
  const auto it = sha256_by_id_.find(id);
  if (it == sha256_by_id_.end()) return absl::NotFoundError(absl::StrCat("no model '", id, "'"));
  const std::string sha256 = it->second;
  sha256_by_id_.erase(it);
  std::error_code error;
  std::filesystem::remove(std::filesystem::path(dir_) / id, error);
  const bool shared = std::any_of(sha256_by_id_.begin(), sha256_by_id_.end(),
                                  [&](const auto& entry) { return entry.second == sha256; });
  if (!shared)
    std::filesystem::remove(std::filesystem::path(dir_) / ContentName(sha256, id), error);
  (void)SyncFolder(dir_);
  return absl::OkStatus();
}

}  // namespace hs
