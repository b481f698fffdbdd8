#pragma once
// `hapticctl train EXERCISE... --server ADDR [--json]`: scores trainees
// live. Attaches to the exercises' scene as a viewer (SessionService.Watch)
// and feeds every frame to one scorer per exercise (each names its
// trainee's tool, so two trainees on two tools are scored at once). Prints
// each trainee's progress once a second, and the summaries when every
// exercise is done (its last target, or its time limit), on Ctrl-C, or
// when the scene or the server goes away (then marked incomplete).

#include <atomic>
#include <ostream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "client/server_call.h"

namespace hs::cli {

struct TrainArgs {
  ConnectionOptions server{};
  /// Exercise files, all of one scene, each for a different tool.
  std::vector<std::string> exercises;
  bool json = false;
  /// Write each trainee's report in DIR/TOOL (report.h), comparing with
  /// these earlier report folders.
  std::string report_dir{};
  std::vector<std::string> compare{};
};

/// Scores until done or `*stop` turns true. kExitOk when every exercise
/// ended (done or interrupted); the gRPC status's exit code when the stream
/// failed (the partial summaries still printed); kExitFailure for bad
/// exercises.
int RunTrain(const TrainArgs& args, std::ostream& out, std::ostream& err,
             const std::atomic<bool>& stop);

/// Adds `train` to `app`; `exit_code` receives its result.
void AddTrainCommand(CLI::App& app, int& exit_code);

}  // namespace hs::cli
