#pragma once
// `hapticctl drive --scene NAME --tool OBJECT (--path FILE | --motion
// press|sweep [--duration S]) [--rate HZ] [--frame-rate-hz HZ] [--json]`: acts as a haptic input
// device. Plays a device path into a scene's tool over
// SessionService.Interact and prints each frame that applies a new pose:
// its contacts and force. With `--operator press|slide|tap` instead, a
// simulated hand drives the tool in a closed loop through a simulated link
// (--latency-ms, --jitter-ms, --loss, --stall-prob, --stall-ms, --seed), rendering from the local
// contact model or not (--local-model on|off), and one summary is printed
// (client/remote/remote_drive.h).

#include <ostream>
#include <string>

#include "CLI/CLI.hpp"
#include "client/haptic_loop/haptic_loop.h"
#include "client/remote/delay_line.h"
#include "client/server_call.h"

namespace hs::cli {

struct DriveArgs {
  ConnectionOptions server;
  std::string scene;
  /// The tool object to drive.
  std::string tool;
  /// Take the tool from the device holding it (an instructor; needs the
  /// admin role on the scene).
  bool take_over = false;
  /// Device path: CSV, one "x,y,z,rx,ry,rz" line per pose sent at --rate,
  /// or JSON lines with times (*.jsonl; see device_path.h).
  std::string path;
  /// Instead of a path: "press" or "sweep" from the tool's pose in the
  /// scene, for `duration_s` seconds (device_path.h).
  std::string motion;
  double duration_s = 2;
  /// The motion's depth and sweep amplitude, metres.
  double depth_m = 0.02;
  double amplitude_m = 0.05;
  /// Poses sent per second (CSV paths, motions and --operator).
  double rate_hz = 1000;
  /// Whether --rate was given: --operator sends poses at the SDK Device's
  /// rate (250 a second) unless it was.
  bool rate_given = false;
  /// Frames a second asked of the server (frame_rate_args.h); 0: its own.
  double frame_rate_hz = 0;
  /// One JSON object (haptics.v1.Frame) per line instead of a table.
  bool json = false;
  /// What the device needs (effect names); empty means everything.
  std::vector<std::string> needs;
  /// A closed-loop operator: "press", "slide" or "tap"; empty for none.
  std::string operator_motion;
  /// "on": render from the local model on the device; "off": apply the
  /// server's forces as they arrive.
  std::string local_model = "on";
  /// With --operator and the local model: the device loop's passivity
  /// controller's largest damping, N*s/m (0: off).
  double passivity_damping_ns_per_m = HapticLoopOptions{}.max_passivity_damping_ns_per_m;
  LinkConditions link;
  /// With --operator: a CSV of the rendered force per tick.
  std::string trace_path;
  /// With --operator: the address of the zero-latency reference run (the
  /// server itself when `server` is a relay); empty for none.
  std::string reference_server;
};

/// Drives the tool and prints to `out`. kExitOk; kExitFailure for a bad
/// path file; else the exit status of the gRPC status (server_call.h),
/// reported on `err`, when the server rejects the stream or ends it with
/// an error.
int RunDrive(const DriveArgs& args, std::ostream& out, std::ostream& err);

/// Adds the `drive` subcommand to `app`; `exit_code` receives its result.
void AddDriveCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
