#include "common/recording/session_files.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/common/scratch_dir.h"

namespace hs {
namespace {

// 2026-11-24 23:05:01.123 UTC.
constexpr int64_t kStart = int64_t{1795561501} * 1'000'000'000 + 123'000'000;

TEST(SessionFilesTest, NamesCarrySceneStartAndPart) {
  EXPECT_EQ(SessionFileName("probe on torus", kStart, 0),
            "probe_on_torus_20261124T230501.123Z.000.hsrec");
  EXPECT_EQ(SessionFileName("demo", kStart, 12), "demo_20261124T230501.123Z.012.hsrec");
}

// The parts after the one given, as far as they go on without a hole;
// a name of another form is a session of one file.
TEST(SessionFilesTest, PartsFollowTheFirst) {
  const std::filesystem::path dir = ScratchDir("parts");
  for (int part : {0, 1, 2, 4}) {
    std::ofstream(dir / SessionFileName("demo", kStart, part)) << "x";
  }
  const std::string first = (dir / SessionFileName("demo", kStart, 0)).string();
  const std::vector<std::string> parts = SessionParts(first);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[2], (dir / SessionFileName("demo", kStart, 2)).string());
  EXPECT_EQ(SessionParts(parts[1]).size(), 2u);
  EXPECT_EQ(SessionParts("/tmp/any.name").size(), 1u);
  EXPECT_EQ(SessionParts("x.hsrec").size(), 1u);
}

}  // namespace
}  // namespace hs
