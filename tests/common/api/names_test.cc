#include "common/api/names.h"

#include <gtest/gtest.h>

#include <string>

namespace hs {
namespace {

// Names of the documented set pass: every allowed character, both lengths
// at the bounds.
TEST(NamesTest, AllowedNamesPass) {
  for (const std::string& name :
       {std::string("a"), std::string("probe on torus"), std::string("peg_in-hole.2"),
        std::string(64, 'Z'), std::string("AZaz09 _.-")}) {
    EXPECT_TRUE(ValidateName(name).ok()) << name;
  }
}

// Each way out of the set is refused, and the message does not repeat the
// name (it may be megabytes or binary).
TEST(NamesTest, OtherNamesAreRefused) {
  for (const std::string& name :
       {std::string(""), std::string(65, 'a'), std::string("tab\t"), std::string("new\nline"),
        std::string("nul\0", 4), std::string("slash/"), std::string(" lead"), std::string("trail "),
        std::string("\xc3\xa9t\xc3\xa9")}) {
    const absl::Status status = ValidateName(name);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << name;
    if (name.size() > 3) {
      EXPECT_EQ(status.message().find(name), std::string::npos) << name;
    }
  }
}

}  // namespace
}  // namespace hs
