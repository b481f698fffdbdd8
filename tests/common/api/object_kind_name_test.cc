#include "common/api/object_kind_name.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace hs {
namespace {

namespace pb = haptics::v1;

// Every kind the API defines has a name of its own, and the rejected or
// unknown ones say so (the oracle: the enum's own descriptor).
TEST(ObjectKindNameTest, EachKindItsOwnName) {
  EXPECT_STREQ(ObjectKindName(pb::OBJECT_KIND_FIXED), "fixed");
  EXPECT_STREQ(ObjectKindName(pb::OBJECT_KIND_TOOL), "tool");
  EXPECT_STREQ(ObjectKindName(pb::OBJECT_KIND_FREE), "free");
  EXPECT_STREQ(ObjectKindName(pb::OBJECT_KIND_UNSPECIFIED), "unspecified");
  EXPECT_STREQ(ObjectKindName(static_cast<pb::ObjectKind>(99)), "unspecified");
  std::set<std::string> names;
  const google::protobuf::EnumDescriptor* kinds = pb::ObjectKind_descriptor();
  for (int i = 0; i < kinds->value_count(); ++i) {
    names.insert(ObjectKindName(static_cast<pb::ObjectKind>(kinds->value(i)->number())));
  }
  EXPECT_EQ(names.size(), static_cast<size_t>(kinds->value_count()));
}

}  // namespace
}  // namespace hs
