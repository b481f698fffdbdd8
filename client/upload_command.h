#pragma once
// `hapticctl upload FILE [--name NAME]`: uploads a model file to a server
// in chunks with its SHA-256 (SceneService.UploadModel) and prints the
// model id to use as ModelSource.uploaded_model_id.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct UploadArgs {
  ConnectionOptions server;
  std::string file;
  /// The model's name on the server; default: the file name without its
  /// extension, characters outside [A-Za-z0-9_.-] replaced by '_'.
  std::string name;
  /// Bytes per chunk.
  int chunk_bytes = 1 << 20;
};

/// Uploads and prints "model_id vertices triangles" to `out`. kExitOk;
/// kExitFailure for an unreadable file; else the exit status of the gRPC
/// status (server_call.h), reported on `err`.
int RunUpload(const UploadArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `upload` subcommand to `app`; `exit_code` receives its result.
void AddUploadCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
