#pragma once
// The scenes a server keeps across restarts (haptic-server --state-dir): one
// row per scene, its name and its spec (serialized haptics.v1.SceneSpec),
// in an SQLite database in WAL mode whose commits reach the disk before
// they return (synchronous = FULL). A change is acknowledged to a client
// only after its row is committed.

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "haptics/v1/scene.pb.h"

struct sqlite3;

namespace hs {

class SceneCatalogue {
 public:
  /// Opens the catalogue at `path`, creating it when the file does not
  /// exist. FAILED_PRECONDITION naming the file when it is no catalogue
  /// (another program's database, another schema version, not a database,
  /// or damaged: SQLite's quick check fails); UNAVAILABLE when it cannot be
  /// opened or written.
  static absl::StatusOr<std::unique_ptr<SceneCatalogue>> Open(const std::string& path);
  ~SceneCatalogue();
  SceneCatalogue(const SceneCatalogue&) = delete;
  SceneCatalogue& operator=(const SceneCatalogue&) = delete;

  /// Keeps `spec` under its name, replacing what the name held; durable
  /// when it returns OK. UNAVAILABLE on a write error (nothing changed).
  absl::Status Put(const haptics::v1::SceneSpec& spec);
  /// Forgets scene `name` (no error when absent); durable when it returns.
  absl::Status Remove(const std::string& name);
  /// Every scene kept, by name. FAILED_PRECONDITION naming the file and
  /// the scene for a row whose spec does not parse.
  absl::StatusOr<std::vector<haptics::v1::SceneSpec>> LoadAll() const;

  const std::string& path() const { return path_; }

 private:
  SceneCatalogue(std::string path, sqlite3* db) : path_(std::move(path)), db_(db) {}
  absl::Status Execute(const char* sql) const;

  std::string path_;
  sqlite3* db_;
};

}  // namespace hs
