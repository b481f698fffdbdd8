#pragma once
// Exit statuses of hapticctl that scripts can rely on.

namespace hs::cli {

/// The command did what was asked.
inline constexpr int kExitOk = 0;
/// The command ran but failed: bad file, rejected request, server error.
inline constexpr int kExitFailure = 1;
/// The command line itself was wrong (unknown flag, missing argument).
inline constexpr int kExitUsage = 2;

}  // namespace hs::cli
