#pragma once
// `hapticctl delete-model MODEL_ID`: deletes an uploaded model
// (SceneService.DeleteModel); refused while a scene uses it.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct DeleteModelArgs {
  ConnectionOptions server;
  std::string model_id;
};

/// Deletes the model and prints "deleted MODEL_ID" to `out`. kExitOk; else
/// the exit status of the gRPC status (server_call.h), reported on `err`.
int RunDeleteModel(const DeleteModelArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `delete-model` subcommand to `app`; `exit_code` receives its result.
void AddDeleteModelCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
