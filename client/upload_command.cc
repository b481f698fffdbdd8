#include "client/upload_command.h"

#include <openssl/evp.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

std::string Sha256(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr);
  return std::string(reinterpret_cast<const char*>(digest), size);
}

std::string DefaultName(const std::filesystem::path& file) {
  std::string name = file.stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  }
  return name.substr(0, 64);
}

}  // namespace

int RunUpload(const UploadArgs& args, std::ostream& out, std::ostream& err) {
  std::ifstream in(args.file, std::ios::binary);
  if (!in) return ReportError("upload", args.file + ": cannot open", err);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  const std::filesystem::path path(args.file);

  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError("upload", channel.status(), err);
  auto stub = pb::SceneService::NewStub(*channel);
  // Large files take longer than one request: the deadline grows with size
  // (at least 1 s per 16 MiB).
  auto context = ContextWithin(args.server.timeout_s + static_cast<double>(bytes.size()) / 16e6);
  pb::UploadModelResponse response;
  auto writer = stub->UploadModel(context.get(), &response);
  pb::UploadModelChunk chunk;
  pb::UploadModelChunk::Header* header = chunk.mutable_header();
  header->set_name(args.name.empty() ? DefaultName(path) : args.name);
  header->set_format(path.extension().string().substr(path.has_extension() ? 1 : 0));
  header->set_size_bytes(static_cast<int64_t>(bytes.size()));
  header->set_sha256(Sha256(bytes));
  size_t offset = 0;
  do {
    const size_t size = std::min(bytes.size() - offset, static_cast<size_t>(args.chunk_bytes));
    chunk.set_data(bytes.substr(offset, size));
    offset += size;
    if (!writer->Write(chunk)) break;  // the server ended the call; Finish says why
    chunk.clear_header();
  } while (offset < bytes.size());
  writer->WritesDone();
  const grpc::Status status = writer->Finish();
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
