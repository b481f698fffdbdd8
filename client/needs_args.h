#pragma once
// --needs: the effects a consumer asks the scene for, by name (simulate,
// drive, loadtest).

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/sim/effects.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

/// The effects named (effect names of common/sim/effects.h); none named
/// means every effect.
absl::StatusOr<EffectSet> ParseNeeds(const std::vector<std::string>& names);

/// The names of `needs`, space-separated.
std::string NeedsNames(const EffectSet& needs);

/// Adds --needs to `cmd`, filling `names`.
void AddNeedsOption(CLI::App& cmd, std::vector<std::string>& names);

/// Sets an Interact stream's open message to ask for `needs` (all: none
/// listed, which the server reads as everything).
void SetNeeds(const EffectSet& needs, haptics::v1::InteractRequest::Open& open);

}  // namespace hs::cli
