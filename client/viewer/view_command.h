#pragma once
// `hapticctl view --server ADDR --scene NAME [--http HOST:PORT]`: the
// browser viewer's bridge (docs/viewer.md), until Ctrl-C or --duration.
// `hapticctl snapshot --server ADDR --scene NAME --out FILE.png [--width W
// --height H]`: the same page, rendered once by headless Chromium.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct ViewArgs {
  ConnectionOptions server;
  std::string scene;
  /// HOST:PORT ([V6]:PORT) to serve the page on.
  std::string http = "127.0.0.1:8080";
  /// PEM certificate (chain) and key: serve https and wss.
  std::string http_tls_cert;
  std::string http_tls_key;
  /// Serve a non-loopback address without TLS all the same.
  bool insecure_http = false;
  /// Seconds to run; 0: until SIGINT or SIGTERM.
  double duration_s = 0;
};

/// Runs the bridge; prints "viewer on URL" (its secret included) to `out`.
/// kExitUsage, before anything listens, for a bad --http, half the TLS
/// pair, or a non-loopback address without TLS or --insecure-http; and
/// for TLS files that do not load.
int RunView(const ViewArgs& args, std::ostream& out, std::ostream& err);

/// Adds `view` and `snapshot` to `app`; `exit_code` receives the result.
void AddViewCommands(CLI::App& app, int& exit_code);

}  // namespace hs::cli
