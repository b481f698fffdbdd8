#include "common/collision/bv_type.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace hs {
namespace {

// Parsing a type's name gives the type back, and the names are distinct.
TEST(BvTypeTest, NamesRoundTrip) {
  std::set<std::string> names;
  for (const BvType type :
       {BvType::kObbRss, BvType::kObb, BvType::kRss, BvType::kKios, BvType::kAabb}) {
    const std::string name(BvTypeName(type));
    EXPECT_TRUE(names.insert(name).second) << name;
    const absl::StatusOr<BvType> parsed = ParseBvType(name);
    ASSERT_TRUE(parsed.ok()) << parsed.status();
    EXPECT_EQ(*parsed, type);
  }
}

// Any other text is INVALID_ARGUMENT naming it and the choices.
TEST(BvTypeTest, UnknownNamesAreRejected) {
  for (const char* name : {"", "OBB", "obb ", "sphere"}) {
    const absl::StatusOr<BvType> parsed = ParseBvType(name);
    ASSERT_EQ(parsed.status().code(), absl::StatusCode::kInvalidArgument) << name;
    EXPECT_NE(parsed.status().message().find("obbrss"), std::string::npos);
  }
}

}  // namespace
}  // namespace hs
