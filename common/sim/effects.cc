#include "common/sim/effects.h"

#include <array>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

constexpr std::array<std::pair<Effect, std::string_view>, kNumEffects> kNames = {{
    {Effect::kCollision, "collision"},
    {Effect::kContactSet, "contact_set"},
    {Effect::kReversingVector, "reversing_vector"},
    {Effect::kForce, "force"},
    {Effect::kFriction, "friction"},
    {Effect::kContinuousCollision, "continuous_collision"},
    {Effect::kFreeBodyMotion, "free_body_motion"},
    {Effect::kLocalModel, "local_model"},
}};

// Each effect and the one it directly needs.
// The reversing vector (the proxy) reads no other stage: it sweeps the tool
// from the proxy toward the device itself.
constexpr std::array<std::pair<Effect, Effect>, 5> kNeeds = {{
    {Effect::kLocalModel, Effect::kReversingVector},
    {Effect::kFriction, Effect::kForce},
    {Effect::kForce, Effect::kReversingVector},
    {Effect::kContactSet, Effect::kCollision},
    {Effect::kContinuousCollision, Effect::kCollision},
}};

}  // namespace

EffectSet WithPrerequisites(EffectSet needed) {
  // kNeeds lists each effect before what it needs, so one pass closes it.
  for (const auto& [effect, prerequisite] : kNeeds) {
    if (needed.Has(effect)) needed = needed.With(prerequisite);
  }
  return needed;
}

EffectSet StagesToRun(EffectSet enabled, EffectSet needed) {
  needed = WithPrerequisites(needed);
  // Continuous collision is how collision is computed, not an output of its
  // own: where the scene enables it, whoever needs collision gets it.
  if (needed.Has(Effect::kCollision)) needed = needed.With(Effect::kContinuousCollision);
  EffectSet run = needed & enabled;
  // Drop stages whose prerequisite does not run, from the bottom up.
  for (auto it = kNeeds.rbegin(); it != kNeeds.rend(); ++it) {
    if (run.Has(it->first) && !run.Has(it->second)) run = run.Without(it->first);
  }
  return run;
}

std::string_view EffectName(Effect effect) { return kNames[static_cast<int>(effect)].second; }

std::vector<std::string_view> EffectNames(EffectSet effects) {
  std::vector<std::string_view> names;
  for (int i = 0; i < kNumEffects; ++i) {
    const auto effect = static_cast<Effect>(i);
    if (effects.Has(effect)) names.push_back(EffectName(effect));
  }
  return names;
}

absl::StatusOr<Effect> ParseEffect(std::string_view name) {
  for (const auto& [effect, n] : kNames) {
    if (n == name) return effect;
  }
  return absl::InvalidArgumentError(absl::StrCat("unknown effect '", std::string(name), "'"));
}

}  // namespace hs
