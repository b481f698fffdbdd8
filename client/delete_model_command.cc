#include "client/delete_model_command.h"

#include <iostream>
#include <memory>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {

namespace pb = haptics::v1;

int RunDeleteModel(const DeleteModelArgs& args, std::ostream& out, std::ostream& err) {
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("delete-model", channel.status(), err);
  pb::DeleteModelRequest request;
  request.set_model_id(args.model_id);
  pb::DeleteModelResponse response;
  const grpc::Status status = pb::SceneService::NewStub(*channel)->DeleteModel(
      ContextWithin(args.server.timeout_s).get(), request, &response);
  if (!status.ok()) return ReportRpcError("delete-model", status, err);
  out << "deleted " << args.model_id << "\n";
  return kExitOk;
}

void AddDeleteModelCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<DeleteModelArgs>();
  CLI::App* cmd = app.add_subcommand("delete-model", "Delete an uploaded model no scene uses");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("MODEL_ID", args->model_id, "The model's id, as upload printed it")->required();
  cmd->callback([args, &exit_code] { exit_code = RunDeleteModel(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
