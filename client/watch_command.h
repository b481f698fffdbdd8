#pragma once
// `hapticctl watch SCENE [--parts poses,contacts,forces] [--summary]
// [--json] [--duration S] [--frames N]`: a viewer (the client SDK's
// Watcher, client/sdk). Prints every frame, or one summary line per second.

#include <ostream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct WatchArgs {
  ConnectionOptions server{};
  std::string scene;
  /// "poses", "contacts", "forces"; empty: all.
  std::vector<std::string> parts;
  /// One line per second: frames, steps, drops, missed steps, contacts,
  /// largest force, tool clashes since the scene began (count and time),
  /// step time; instead of one line per frame.
  bool summary = false;
  /// JSON lines (haptics.v1.Frame, or the summary's fields).
  bool json = false;
  /// Stop after this many seconds (0: when the stream ends).
  double duration_s = 0;
  /// Stop after this many frames (0: no limit).
  int64_t max_frames = 0;
};

/// Watches and prints to `out`. kExitOk when it stopped at --duration or
/// --frames, or the stream ended normally; else the exit status of the
/// gRPC status (server_call.h), reported on `err` (kExitUnavailable when
/// the scene is deleted or the server shuts down).
int RunWatch(const WatchArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `watch` subcommand to `app`; `exit_code` receives its result.
void AddWatchCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
