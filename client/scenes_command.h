#pragma once
// `hapticctl scenes list|create SCENE_FILE|show NAME|delete NAME`: the
// scenes a server holds (SceneService).

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/server_call.h"
#include "haptics/v1/scene_service.pb.h"

namespace hs::cli {

struct ScenesArgs {
  ConnectionOptions server;
  /// "list", "create", "show" or "delete".
  std::string action;
  /// create: a scene file (haptics.v1.SceneSpec, text format or JSON).
  std::string scene_file;
  /// show, delete: the scene's name; create: replaces the file's name.
  std::string name;
  /// SceneInfo messages as JSON (one line each) instead of text.
  bool json = false;
};

/// One line for `info` (name, step, triangles, streams, revision), then
/// with `with_objects` a line per object; with `json` the SceneInfo as
/// one line of JSON.
void PrintSceneInfo(const haptics::v1::SceneInfo& info, bool json, bool with_objects,
                    std::ostream& out);

/// Runs the action and prints to `out`. kExitOk; kExitFailure for an
/// unreadable scene file; else the exit status of the gRPC status
/// (server_call.h), reported on `err`.
int RunScenes(const ScenesArgs& args, std::ostream& out, std::ostream& err);

/// Adds `scenes` and its four subcommands to `app`; `exit_code` receives
/// the result.
void AddScenesCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
