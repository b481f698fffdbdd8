#include "server/state/scene_catalogue.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

pb::SceneSpec Spec(const std::string& name, double step_s) {
  pb::SceneSpec spec;
  spec.set_name(name);
  spec.set_step_s(step_s);
  return spec;
}

// What is put is loaded back, by name, after the catalogue is closed and
// opened again; a put replaces the name's spec, a removal forgets it.
TEST(SceneCatalogueTest, KeepsAcrossReopening) {
  const std::string path = (ScratchDir("keeps") / "scenes.db").string();
  {
    auto catalogue = *SceneCatalogue::Open(path);
    ASSERT_TRUE(catalogue->Put(Spec("b", 0.001)).ok());
    ASSERT_TRUE(catalogue->Put(Spec("a", 0.002)).ok());
    ASSERT_TRUE(catalogue->Put(Spec("b", 0.004)).ok());
    ASSERT_TRUE(catalogue->Put(Spec("c", 0.001)).ok());
    ASSERT_TRUE(catalogue->Remove("c").ok());
    ASSERT_TRUE(catalogue->Remove("never there").ok());
  }
  auto catalogue = SceneCatalogue::Open(path);
  ASSERT_TRUE(catalogue.ok()) << catalogue.status();
  const auto specs = (*catalogue)->LoadAll();
  ASSERT_TRUE(specs.ok()) << specs.status();
  ASSERT_EQ(specs->size(), 2u);
  EXPECT_EQ((*specs)[0].name(), "a");
  EXPECT_EQ((*specs)[0].step_s(), 0.002);
  EXPECT_EQ((*specs)[1].name(), "b");
  EXPECT_EQ((*specs)[1].step_s(), 0.004);
}

// Not a catalogue: a file of text, another program's SQLite database, a
// catalogue with a row that is no spec. Each is refused, naming the file,
// and the file is left as it was.
TEST(SceneCatalogueTest, RefusesWhatIsNoCatalogue) {
  const std::filesystem::path dir = ScratchDir("foreign");
  const std::string text = (dir / "text.db").string();
  std::ofstream(text) << "This is no database at all, only some text long enough to be read.";
  const auto from_text = SceneCatalogue::Open(text);
  EXPECT_EQ(from_text.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(from_text.status().message().find(text), std::string::npos) << from_text.status();

  const std::string other = (dir / "other.db").string();
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(other.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE t (x INTEGER)", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  }
  const auto before = std::filesystem::file_size(other);
  const auto from_other = SceneCatalogue::Open(other);
  EXPECT_EQ(from_other.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(from_other.status().message().find("not a scene catalogue"), std::string::npos)
      << from_other.status();
  EXPECT_EQ(std::filesystem::file_size(other), before);

  const std::string bad_row = (dir / "bad_row.db").string();
  ASSERT_TRUE(SceneCatalogue::Open(bad_row).ok());
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(bad_row.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(
        sqlite3_exec(db, "INSERT INTO scenes VALUES ('x', X'FFFFFFFF')", nullptr, nullptr, nullptr),
        SQLITE_OK);
    sqlite3_close(db);
  }
  const auto loaded = (*SceneCatalogue::Open(bad_row))->LoadAll();
  EXPECT_EQ(loaded.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(loaded.status().message().find("'x'"), std::string::npos) << loaded.status();
}

}  // namespace
}  // namespace hs
