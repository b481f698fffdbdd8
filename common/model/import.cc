#include "common/model/import.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/model/assimp_reader.h"
#include "common/model/cleaning.h"
#include "common/model/coin_lock.h"
#include "common/model/coin_reader.h"
#include "common/model/raw_mesh.h"
#include "common/model/triangulate.h"

namespace hs {
namespace {

// The same status with the file named in front of its message.
absl::Status ForFile(const std::string& path, const absl::Status& status) {
  return absl::Status(status.code(), absl::StrCat(path, ": ", status.message()));
}

// NOT_FOUND, PERMISSION_DENIED or INVALID_ARGUMENT when `path` is not a
// readable, non-empty regular file. Messages do not name the file.
absl::Status CheckFile(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found) {
    return absl::NotFoundError("no such file");
  }
  if (error) return absl::InvalidArgumentError(absl::StrCat("cannot stat: ", error.message()));
  if (status.type() == std::filesystem::file_type::directory) {
    return absl::InvalidArgumentError("is a directory, not a model file");
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    const int open_errno = errno;
    const std::string reason = std::strerror(open_errno);
    if (open_errno == EACCES || open_errno == EPERM) {
      return absl::PermissionDeniedError(absl::StrCat("cannot open for reading: ", reason));
    }
    if (open_errno == ENOENT) return absl::NotFoundError("no such file");
    return absl::InvalidArgumentError(absl::StrCat("cannot open for reading: ", reason));
  }
  const bool empty = std::fgetc(file) == EOF;
  std::fclose(file);
  if (empty) return absl::InvalidArgumentError("the file is empty");
  return absl::OkStatus();
}

bool ReadsWithCoin(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".iv" || extension == ".wrl";
}

// The HapticObject of the polygons a reader made of file `path`, or the
// reader's error.
absl::StatusOr<ImportedModel> Build(absl::StatusOr<RawMesh> raw, const std::string& path,
                                    bool coin, const ImportOptions& options) {
  if (!raw.ok()) return raw.status();
  if (absl::Status status = ValidateRawMesh(*raw); !status.ok()) return status;
  const std::vector<FaceInput> triangles = TriangulatePolygons(*raw);
  absl::StatusOr<CleanedMesh> cleaned = CleanMesh(*raw, triangles, options);
  if (!cleaned.ok()) return cleaned.status();
  absl::StatusOr<HapticObject> object =
      HapticObject::Create(std::filesystem::path(path).stem().string(), std::move(cleaned->mesh));
  if (!object.ok()) return object.status();
  return ImportedModel{*std::move(object), cleaned->report, coin ? "coin3d" : "assimp"};
}

absl::Status CheckOptions(const ImportOptions& options) {
  if (absl::Status status = ValidateImportOptions(options); !status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("bad import options: ", status.message()));
  }
  return absl::OkStatus();
}

// Runs `import` with the file named in front of its messages, behind the
// last exception barrier.
template <class Import>
absl::StatusOr<ImportedModel> ForFileGuarded(const std::string& path, Import import) {
  absl::StatusOr<ImportedModel> model;
  try {
    model = import();
  } catch (const std::exception& e) {
    // The readers catch what assimp and Coin throw; this is the last barrier
    // (std::bad_alloc from a header that promises billions of vertices).
    model = absl::InvalidArgumentError(absl::StrCat("import failed: ", e.what()));
  } catch (...) {
    model = absl::InvalidArgumentError("import failed with an unknown exception");
  }
  if (!model.ok()) return ForFile(path, model.status());
  return model;
}

}  // namespace

absl::StatusOr<ImportedModel> ImportModel(const std::string& path, const ImportOptions& options) {
  return ForFileGuarded(path, [&]() -> absl::StatusOr<ImportedModel> {
    if (absl::Status status = CheckOptions(options); !status.ok()) return status;
    if (absl::Status status = CheckFile(path); !status.ok()) return status;
    const bool coin = ReadsWithCoin(path);
    return Build(coin ? ReadWithCoin(path) : ReadWithAssimp(path), path, coin, options);
  });
}

absl::StatusOr<ImportedModel> ImportModelBytes(absl::string_view bytes,
                                               const std::string& file_name,
                                               const ImportOptions& options) {
  return ForFileGuarded(file_name, [&]() -> absl::StatusOr<ImportedModel> {
    if (absl::Status status = CheckOptions(options); !status.ok()) return status;
    if (bytes.empty()) return absl::InvalidArgumentError("the file is empty");
    const bool coin = ReadsWithCoin(file_name);
    return Build(coin ? ReadBytesWithCoin(bytes) : ReadBytesWithAssimp(bytes, file_name),
                 file_name, coin, options);
  });
}

void PrepareReaders() { InitCoinOnce(); }

}  // namespace hs
