// hapticctl: the command-line client of the haptic simulation service.
// Only wiring: each subcommand lives in its own *_command.cc.

#include <iostream>

#include "CLI/CLI.hpp"
#include "client/contact_command.h"
#include "client/delete_model_command.h"
#include "client/drive_command.h"
#include "client/exit_codes.h"
#include "client/health_command.h"
#include "client/inspect_command.h"
#include "client/loadtest/loadtest_command.h"
#include "client/objects_command.h"
#include "client/recording_command.h"
#include "client/relay/relay_command.h"
#include "client/replay_command.h"
#include "client/scenes_command.h"
#include "client/simulate_command.h"
#include "client/training/score_command.h"
#include "client/training/train_command.h"
#include "client/upload_command.h"
#include "client/viewer/view_command.h"
#include "client/watch_command.h"

int main(int argc, char** argv) {
  CLI::App app{"hapticctl: client of the haptic simulation service"};
  app.require_subcommand(1);
  int exit_code = hs::cli::kExitOk;
  hs::cli::AddInspectCommand(app, exit_code);
  hs::cli::AddContactCommand(app, exit_code);
  hs::cli::AddSimulateCommand(app, exit_code);
  hs::cli::AddScenesCommand(app, exit_code);
  hs::cli::AddUploadCommand(app, exit_code);
  hs::cli::AddDeleteModelCommand(app, exit_code);
  hs::cli::AddObjectsCommand(app, exit_code);
  hs::cli::AddHealthCommand(app, exit_code);
  hs::cli::AddWatchCommand(app, exit_code);
  hs::cli::AddDriveCommand(app, exit_code);
  hs::cli::AddRelayCommand(app, exit_code);
  hs::cli::AddLoadtestCommand(app, exit_code);
  hs::cli::AddRecordingCommand(app, exit_code);
  hs::cli::AddReplayCommand(app, exit_code);
  hs::cli::AddViewCommands(app, exit_code);
  hs::cli::AddScoreCommand(app, exit_code);
  hs::cli::AddTrainCommand(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& e) {
    // Options belong to a subcommand; CLI11's own message would list the
    // ones given before it backwards.
    if (argc > 1 && argv[1][0] == '-') {
      std::cerr << "hapticctl: options go after the subcommand (hapticctl SUBCOMMAND "
                   "[OPTIONS]); not expected before it: "
                << argv[1] << "\nRun with --help for more information.\n";
      return hs::cli::kExitUsage;
    }
    app.exit(e);
    return hs::cli::kExitUsage;
  } catch (const CLI::ParseError& e) {
    const int parse_code = app.exit(e);
    return parse_code == 0 ? hs::cli::kExitOk : hs::cli::kExitUsage;
  }
  return exit_code;
}
