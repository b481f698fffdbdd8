#include "client/needs_args.h"

#include "client/pose_args.h"
#include "common/api/proto_convert.h"

namespace hs::cli {

absl::StatusOr<EffectSet> ParseNeeds(const std::vector<std::string>& names) {
  if (names.empty()) return EffectSet::Default();
  EffectSet needs;
  for (const std::string& name : names) {
    absl::StatusOr<Effect> effect = ParseEffect(name);
    if (!effect.ok()) return effect.status();
    needs = needs.With(*effect);
  }
  return needs;
}

std::string NeedsNames(const EffectSet& needs) {
  std::string names;
  for (std::string_view name : EffectNames(needs)) {
    if (!names.empty()) names += ' ';
    names += name;
  }
  return names;
}

void AddNeedsOption(CLI::App& cmd, std::vector<std::string>& names) {
  cmd.add_option("--needs", names,
                 "Effects the consumer needs (collision, contact_set, reversing_vector, force, "
                 "friction, continuous_collision, free_body_motion, local_model); default all "
                 "but local_model. A haptic device needs 'force friction', a remote one "
                 "'force friction local_model'")
      ->check(
          ValueCheck("EFFECT", [](const std::string& name) { return ParseEffect(name).status(); }));
}

void SetNeeds(const EffectSet& needs, haptics::v1::InteractRequest::Open& open) {
  open.clear_needs();
  if (needs != EffectSet::Default()) EffectsToProto(needs, open.mutable_needs());
}

}  // namespace hs::cli
