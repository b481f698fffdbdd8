#include "common/sim/effects.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

// Force pulls in the reversing vector (the proxy), neither collision nor
// the contact set; friction pulls in force; the contact set and continuous
// collision pull in collision.
TEST(EffectsTest, PrerequisitesClose) {
  EXPECT_EQ(WithPrerequisites({Effect::kFriction}),
            (EffectSet{Effect::kFriction, Effect::kForce, Effect::kReversingVector}));
  EXPECT_EQ(WithPrerequisites({Effect::kContactSet}),
            (EffectSet{Effect::kContactSet, Effect::kCollision}));
  EXPECT_EQ(WithPrerequisites({Effect::kContinuousCollision}),
            (EffectSet{Effect::kContinuousCollision, Effect::kCollision}));
  EXPECT_EQ(WithPrerequisites({Effect::kCollision}), (EffectSet{Effect::kCollision}));
}

// A stage runs only when enabled and needed, and not when a prerequisite is disabled.
TEST(EffectsTest, StagesToRun) {
  EXPECT_EQ(StagesToRun(EffectSet::All(), {Effect::kCollision}),
            (EffectSet{Effect::kCollision, Effect::kContinuousCollision}));
  EXPECT_EQ(StagesToRun({Effect::kCollision}, {Effect::kCollision}),
            (EffectSet{Effect::kCollision}));
  EXPECT_EQ(StagesToRun({Effect::kCollision}, {Effect::kForce}), EffectSet());
  EXPECT_EQ(StagesToRun(EffectSet::All(), {Effect::kForce}),
            (EffectSet{Effect::kForce, Effect::kReversingVector}));
  const EffectSet no_proxy = EffectSet::All().Without(Effect::kReversingVector);
  EXPECT_EQ(StagesToRun(no_proxy, {Effect::kForce, Effect::kCollision}),
            (EffectSet{Effect::kCollision, Effect::kContinuousCollision}));
  EXPECT_EQ(StagesToRun(EffectSet::All(), EffectSet()), EffectSet());
}

// Names round-trip; unknown names are rejected.
TEST(EffectsTest, Names) {
  for (int i = 0; i < kNumEffects; ++i) {
    const auto e = static_cast<Effect>(i);
    EXPECT_EQ(*ParseEffect(EffectName(e)), e);
  }
  EXPECT_FALSE(ParseEffect("gravity").ok());
  EXPECT_EQ(EffectNames({Effect::kForce, Effect::kCollision}),
            (std::vector<std::string_view>{"collision", "force"}));
  EXPECT_TRUE(EffectNames(EffectSet()).empty());
}

}  // namespace
}  // namespace hs
