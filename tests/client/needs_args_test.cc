#include "client/needs_args.h"

#include <gtest/gtest.h>

#include "common/api/proto_convert.h"

namespace hs::cli {
namespace {

// No names means every effect; names give exactly those; an unknown name
// is an error that names it.
TEST(NeedsArgsTest, Parse) {
  EXPECT_EQ(*ParseNeeds({}), EffectSet::Default());
  EXPECT_EQ(*ParseNeeds({"force", "friction"}), (EffectSet{Effect::kForce, Effect::kFriction}));
  const absl::StatusOr<EffectSet> bad = ParseNeeds({"force", "gravity"});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("gravity"), std::string::npos);
}

// The default needs go out as an empty list (the server reads it as the
// default); a subset goes out effect by effect, and the server reads back
// the same set.
TEST(NeedsArgsTest, OpenMessage) {
  haptics::v1::InteractRequest::Open open;
  SetNeeds(EffectSet::Default(), open);
  EXPECT_EQ(open.needs_size(), 0);
  const EffectSet force{Effect::kForce, Effect::kFriction};
  SetNeeds(force, open);
  EXPECT_EQ(open.needs_size(), 2);
  EXPECT_EQ(*EffectsFromProto(open.needs(), EffectSet::All(), "needs"), force);
  EXPECT_EQ(NeedsNames(force), "force friction");
}

}  // namespace
}  // namespace hs::cli
