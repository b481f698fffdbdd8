#include "client/health_command.h"

#include <iostream>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/health_check.h"

namespace hs::cli {

int RunHealth(const HealthArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("health", channel.status(), err);
  int serving = 0;
  const grpc::Status status = CheckHealth(*channel, args.service, args.server.timeout_s, &serving);
  if (!status.ok()) return ReportRpcError("health", status, err);
  out << ServingStatusName(serving) << "\n";
  return serving == kServing ? kExitOk : kExitNotServing;
}

void AddHealthCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<HealthArgs>();
  CLI::App* cmd = app.add_subcommand("health", "Is the server serving? (grpc.health.v1)");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("--service", args->service,
                  "A service's full name, e.g. haptics.v1.SceneService (default: the server)");
  cmd->callback([args, &exit_code] { exit_code = RunHealth(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
