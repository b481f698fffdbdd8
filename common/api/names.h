#pragma once
// The names clients give scenes and objects: they come back in every
// listing and frame, end up in logs and metrics, and are typed on command
// lines, so they are short, printable and plain.

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace hs {

/// Longest scene or object name, characters.
inline constexpr size_t kMaxNameLength = 64;

/// OK for 1..kMaxNameLength characters of [A-Za-z0-9 _.-] that neither
/// start nor end with a space; INVALID_ARGUMENT saying what is wrong
/// otherwise (the name itself is not repeated: it may be huge or binary).
absl::Status ValidateName(absl::string_view name);

}  // namespace hs
