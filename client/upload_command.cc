#include "client/upload_command.h"

#include <fstream>
#include <iostream>
#include <sstream>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/model_upload.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {
namespace pb = haptics::v1;

int RunUpload(const UploadArgs& args, std::ostream& out, std::ostream& err) {
  std::ifstream in(args.file, std::ios::binary);
  if (!in) return ReportError("upload", args.file + ": cannot open", err);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();

  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("upload", channel.status(), err);
  auto stub = pb::SceneService::NewStub(*channel);
  pb::UploadModelResponse response;
  const grpc::Status status =
      UploadModelBytes(*stub, bytes, args.name.empty() ? DefaultModelName(args.file) : args.name,
                       ModelFormat(args.file), static_cast<size_t>(args.chunk_bytes),
                       args.server.timeout_s, &response);
  if (!status.ok()) return ReportRpcError("upload", status, err);
  out << response.model_id() << " " << response.vertices() << " vertices " << response.triangles()
      << " triangles\n";
  return kExitOk;
}

void AddUploadCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<UploadArgs>();
  CLI::App* cmd = app.add_subcommand(
      "upload", "Upload a model file; prints its model id (ModelSource.uploaded_model_id)");
  AddConnectionOptions(*cmd, args->server);
  cmd->add_option("FILE", args->file, "Model file (obj, stl, ply, off, ...)")->required();
  cmd->add_option("--name", args->name, "Model name on the server (default: the file's stem)");
  cmd->add_option("--chunk-bytes", args->chunk_bytes, "Bytes per message")
      ->check(CLI::Range(1, 8 << 20))
      ->capture_default_str();
  cmd->callback([args, &exit_code] { exit_code = RunUpload(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
