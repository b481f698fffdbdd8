#include "server/state/scene_catalogue.h"

#include <sqlite3.h>

#include <filesystem>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

// PRAGMA application_id of a catalogue ("HSsc") and its schema version.
constexpr int kApplicationId = 0x48537363;
constexpr int kSchemaVersion = 1;

// One prepared statement, finalized when it goes.
using Statement = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

absl::StatusOr<Statement> Prepare(sqlite3* db, const char* sql, const std::string& path) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &raw, nullptr) != SQLITE_OK) {
    return absl::UnavailableError(absl::StrCat(path, ": ", sqlite3_errmsg(db)));
  }
  return Statement(raw, &sqlite3_finalize);
}

// The single integer a PRAGMA query returns.
absl::StatusOr<int> PragmaInt(sqlite3* db, const char* sql, const std::string& path) {
  absl::StatusOr<Statement> statement = Prepare(db, sql, path);
  if (!statement.ok()) return statement.status();
  if (sqlite3_step(statement->get()) != SQLITE_ROW) {
    return absl::FailedPreconditionError(
        absl::StrCat(path, " is not a scene catalogue: ", sqlite3_errmsg(db)));
  }
  return sqlite3_column_int(statement->get(), 0);
}

}  // namespace

absl::StatusOr<std::unique_ptr<SceneCatalogue>> SceneCatalogue::Open(const std::string& path) {
  const bool existed = std::filesystem::exists(path);
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
      SQLITE_OK) {
    const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    return absl::UnavailableError(absl::StrCat("cannot open ", path, ": ", why));
  }
  std::unique_ptr<SceneCatalogue> catalogue(new SceneCatalogue(path, db));
  sqlite3_busy_timeout(db, 5000);
  if (existed) {
    // Another program's database, another version of ours, or not a
    // database at all: refused before anything is written to it.
    absl::StatusOr<int> id = PragmaInt(db, "PRAGMA application_id", path);
    if (!id.ok()) return id.status();
    absl::StatusOr<int> version = PragmaInt(db, "PRAGMA user_version", path);
    if (!version.ok()) return version.status();
    if (*id != kApplicationId || *version != kSchemaVersion) {
      return absl::FailedPreconditionError(
          absl::StrCat(path, " is not a scene catalogue of this server (application id ", *id,
                       ", schema version ", *version, ")"));
    }
    absl::StatusOr<Statement> check = Prepare(db, "PRAGMA quick_check", path);
    if (!check.ok()) return check.status();
    if (sqlite3_step(check->get()) != SQLITE_ROW ||
        std::string(reinterpret_cast<const char*>(sqlite3_column_text(check->get(), 0))) != "ok") {
      return absl::FailedPreconditionError(absl::StrCat(path, " is damaged: ", sqlite3_errmsg(db)));
    }
  }
  for (const char* sql : {"PRAGMA journal_mode = WAL", "PRAGMA synchronous = FULL"}) {
    if (absl::Status s = catalogue->Execute(sql); !s.ok()) return s;
  }
  if (!existed) {
    const std::string schema =
        absl::StrCat("BEGIN; CREATE TABLE scenes (name TEXT PRIMARY KEY, spec BLOB NOT NULL);",
                     "PRAGMA application_id = ", kApplicationId,
                     "; PRAGMA user_version = ", kSchemaVersion, "; COMMIT;");
    if (absl::Status s = catalogue->Execute(schema.c_str()); !s.ok()) return s;
  }
  return catalogue;
}

SceneCatalogue::~SceneCatalogue() { sqlite3_close(db_); }

absl::Status SceneCatalogue::Execute(const char* sql) const {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : sqlite3_errmsg(db_);
    sqlite3_free(error);
    return absl::UnavailableError(absl::StrCat(path_, ": ", why));
  }
  return absl::OkStatus();
}

absl::Status SceneCatalogue::Put(const haptics::v1::SceneSpec& spec) {
  const std::string bytes = spec.SerializeAsString();
  absl::StatusOr<Statement> statement =
      Prepare(db_, "INSERT OR REPLACE INTO scenes (name, spec) VALUES (?1, ?2)", path_);
  if (!statement.ok()) return statement.status();
  sqlite3_bind_text(statement->get(), 1, spec.name().data(), static_cast<int>(spec.name().size()),
                    SQLITE_TRANSIENT);
  sqlite3_bind_blob(statement->get(), 2, bytes.data(), static_cast<int>(bytes.size()),
                    SQLITE_TRANSIENT);
  if (sqlite3_step(statement->get()) != SQLITE_DONE) {
    return absl::UnavailableError(absl::StrCat(path_, ": ", sqlite3_errmsg(db_)));
  }
  return absl::OkStatus();
}

absl::Status SceneCatalogue::Remove(const std::string& name) {
  absl::StatusOr<Statement> statement = Prepare(db_, "DELETE FROM scenes WHERE name = ?1", path_);
  if (!statement.ok()) return statement.status();
  sqlite3_bind_text(statement->get(), 1, name.data(), static_cast<int>(name.size()),
                    SQLITE_TRANSIENT);
  if (sqlite3_step(statement->get()) != SQLITE_DONE) {
    return absl::UnavailableError(absl::StrCat(path_, ": ", sqlite3_errmsg(db_)));
  }
  return absl::OkStatus();
}

absl::StatusOr<std::vector<haptics::v1::SceneSpec>> SceneCatalogue::LoadAll() const {
  absl::StatusOr<Statement> statement =
      Prepare(db_, "SELECT name, spec FROM scenes ORDER BY name", path_);
  if (!statement.ok()) return statement.status();
  std::vector<haptics::v1::SceneSpec> specs;
  int result;
  while ((result = sqlite3_step(statement->get())) == SQLITE_ROW) {
    const std::string name(reinterpret_cast<const char*>(sqlite3_column_text(statement->get(), 0)));
    const void* blob = sqlite3_column_blob(statement->get(), 1);
    const int size = sqlite3_column_bytes(statement->get(), 1);
    haptics::v1::SceneSpec& spec = specs.emplace_back();
    if (!spec.ParseFromArray(blob, size) || spec.name() != name) {
      return absl::FailedPreconditionError(
          absl::StrCat(path_, ": the spec of scene '", name, "' does not parse"));
    }
  }
  if (result != SQLITE_DONE) {
    return absl::FailedPreconditionError(absl::StrCat(path_, ": ", sqlite3_errmsg(db_)));
  }
  return specs;
}

}  // namespace hs
