#pragma once
// `hapticctl view --server ADDR --scene NAME [--http HOST:PORT]`: the
// browser viewer's bridge (docs/viewer.md), until Ctrl-C or --duration.
// `hapticctl snapshot --server ADDR --scene NAME --out FILE.png [--width W
// --height H]`: the same page, rendered once by headless Chromium.

#include "CLI/CLI.hpp"

namespace hs::cli {

/// Adds `view` and `snapshot` to `app`; `exit_code` receives the result.
void AddViewCommands(CLI::App& app, int& exit_code);

}  // namespace hs::cli
