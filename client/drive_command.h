#pragma once
// `hapticctl drive --server ADDR --scene NAME --tool OBJECT --path FILE.csv
// [--rate HZ] [--json]`: acts as a haptic input device. Plays a device path
// into a scene's tool over SessionService.Interact at a fixed rate and
// prints each frame that applies a new pose: its contacts and force.

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"

namespace hs::cli {

struct DriveArgs {
  /// host:port of haptic-server.
  std::string server = "127.0.0.1:50051";
  std::string scene;
  /// The tool object to drive.
  std::string tool;
  /// Device path, one "x,y,z,rx,ry,rz" line per pose (see tool_path.h).
  std::string path;
  /// Poses sent per second.
  double rate_hz = 1000;
  /// One JSON object (haptics.v1.Frame) per line instead of a table.
  bool json = false;
};

/// Drives the tool and prints to `out`. kExitOk; kExitFailure with the
/// gRPC status on `err` when the server rejects the stream or ends it
/// with an error.
int RunDrive(const DriveArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `drive` subcommand to `app`; `exit_code` receives its result.
void AddDriveCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
