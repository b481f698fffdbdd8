#include "server/auth/token_table.h"

#include <gtest/gtest.h>

#include "absl/strings/match.h"

namespace hs {
namespace {

// SHA-256("abc"), the FIPS 180-2 example.
constexpr char kAbcDigest[] = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";

// A token is found by the SHA-256 the file lists, with its role, pattern
// and a caller name made of the digest's first 12 digits; comments, blank
// lines, tabs and upper-case hex are fine.
TEST(TokenTableTest, FindsTokensByTheirDigest) {
  const std::string text =
      std::string("# trainers\n\n  sha256:") + kAbcDigest + "\tdrive   train-*  \nSHA256:" +
      "E3B0C44298FC1C149AFBF4C8996FB92427AE41E4649B934CA495991B7852B855 admin * dr.lee@ward-3\n";
  absl::StatusOr<TokenTable> table = TokenTable::Parse(text, "tokens");
  ASSERT_TRUE(table.ok()) << table.status();
  EXPECT_EQ(table->size(), 2u);
  const Grant* abc = table->Find("abc");
  ASSERT_NE(abc, nullptr);
  EXPECT_EQ(abc->role, Role::kDrive);
  EXPECT_EQ(abc->scene_pattern, "train-*");
  EXPECT_EQ(abc->caller, "token:ba7816bf8f01");
  EXPECT_EQ(abc->name, "token:ba7816bf8f01");  // no NAME: the caller
  const Grant* empty = table->Find("");        // SHA-256 of no bytes
  ASSERT_NE(empty, nullptr);
  EXPECT_EQ(empty->role, Role::kAdmin);
  EXPECT_EQ(empty->name, "dr.lee@ward-3");
  EXPECT_EQ(table->Find("abcd"), nullptr);
  EXPECT_EQ(table->Find(kAbcDigest), nullptr);  // the digest is not the token
}

// Each malformed line is refused with the file and line it is on.
TEST(TokenTableTest, RefusesMalformedLines) {
  const std::string good = std::string("sha256:") + kAbcDigest;
  const struct {
    std::string line;
    std::string message;
  } cases[] = {
      {good + " admin", "expected 'sha256:<hex> ROLE SCENE_PATTERN [NAME]'"},
      {good + " admin * name extra", "expected"},
      {good + " admin * bad/name", "NAME must be"},
      {good + " admin * " + std::string(65, 'a'), "NAME must be"},
      {std::string(kAbcDigest) + " admin *", "sha256: and 64 hex digits"},
      {good.substr(0, good.size() - 1) + " admin *", "64 hex digits"},
      {good.substr(0, good.size() - 1) + "g admin *", "64 hex digits"},
      {good + " root *", "unknown role 'root'"},
  };
  for (const auto& c : cases) {
    absl::StatusOr<TokenTable> table = TokenTable::Parse("# first\n" + c.line + "\n", "t.txt");
    ASSERT_FALSE(table.ok()) << c.line;
    EXPECT_EQ(table.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_TRUE(absl::StartsWith(table.status().message(), "t.txt:2: ")) << table.status();
    EXPECT_NE(table.status().message().find(c.message), std::string::npos) << table.status();
  }
  absl::StatusOr<TokenTable> twice =
      TokenTable::Parse(good + " admin *\n" + good + " watch *\n", "t.txt");
  ASSERT_FALSE(twice.ok());
  EXPECT_NE(twice.status().message().find("t.txt:2: this token is listed twice"),
            std::string::npos);
  EXPECT_FALSE(TokenTable::Read("/nonexistent/tokens").ok());
}

}  // namespace
}  // namespace hs
