#pragma once
// `hapticctl loadtest --clients N --rate HZ --duration S [--frame-rate-hz
// HZ] [--scene FILE] [--viewers M] [--json] [--allow-remote] [--server-pid
// PID] [--server-metrics URL] [--no-echo]`: runs the load test of
// loadtest.h and prints its report (report_text.h, report_json.h).

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/loadtest/loadtest.h"
#include "client/loadtest/report_json.h"

namespace hs::cli {

struct LoadtestArgs {
  LoadtestOptions options;
  /// A scene file (haptics.v1.SceneSpec); empty: the built-in demo scene.
  std::string scene_file;
  /// The report as one JSON object instead of text.
  bool json = false;
  /// What each device needs (effect names); empty means everything.
  std::vector<std::string> needs;
};

/// Runs the test, progress lines on `err`, and prints the report to `out`.
/// kExitOk; kExitUsage for options past the bounds or a remote server
/// without --allow-remote; kExitFailure for an unreadable scene file; else
/// the exit status of the server's status code (server_call.h).
int RunLoadtestCommand(const LoadtestArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `loadtest` subcommand to `app`; `exit_code` receives its result.
void AddLoadtestCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
