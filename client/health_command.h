#pragma once
// `hapticctl health [--service NAME]`: asks the server's grpc.health.v1
// Health service whether it is serving.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct HealthArgs {
  ConnectionOptions server;
  /// A service name ("haptics.v1.SceneService", ...); empty: the server.
  std::string service;
};

/// Prints SERVING, NOT_SERVING, UNKNOWN or SERVICE_UNKNOWN to `out`.
/// kExitOk when SERVING, kExitNotServing when the server answers
/// otherwise; else the exit status of the gRPC status (server_call.h):
/// kExitUnavailable when it cannot be reached, kExitNotFound for an unknown
/// service.
int RunHealth(const HealthArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `health` subcommand to `app`; `exit_code` receives its result.
void AddHealthCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
