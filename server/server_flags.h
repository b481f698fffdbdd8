#pragma once
// haptic-server's command line and environment, read into what the server
// and its Agones lifecycle start with. The flags, their defaults and checks
// are stated here once; docs/server.md lists them.

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "server/agones/agones_lifecycle.h"
#include "server/haptic_server.h"

namespace hs {

/// What haptic-server was asked to do.
struct ServerFlags {
  ServerOptions server;
  /// sdk_port from AGONES_SDK_HTTP_PORT (0: not on Agones), the rest from
  /// the --agones-* flags.
  AgonesOptions agones;
  /// --scene files, in the order given.
  std::vector<std::string> scene_files;
  /// --metrics host:port; empty: no metrics endpoint.
  std::string metrics_address;
  /// --cpus, sorted, each one the process may run on; empty: not given.
  std::vector<int> cpus;
};

/// The exit status of a command line or environment that cannot be run.
inline constexpr int kServerExitUsage = 2;

/// Either the flags to start with, or the status to exit with at once.
struct ParsedServerFlags {
  std::optional<ServerFlags> flags;
  /// When `flags` is empty: 0 after --help, kServerExitUsage after a bad
  /// flag or environment value.
  int exit_code = 0;
};

/// Reads an environment variable: nullptr when unset (std::getenv).
using EnvironmentReader = std::function<const char*(const char*)>;

/// Parses `argv` (`argc` entries, the program's name first) and the
/// environment as read by `getenv`. --help prints the usage on `out`; a bad
/// flag or value (unknown flag, value out of range, missing file) or an
/// AGONES_SDK_HTTP_PORT that is no port prints a message on `err`.
ParsedServerFlags ParseServerFlags(int argc, const char* const* argv,
                                   const EnvironmentReader& getenv, std::ostream& out,
                                   std::ostream& err);

}  // namespace hs
