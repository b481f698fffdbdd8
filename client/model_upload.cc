#include "client/model_upload.h"

#include <openssl/evp.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

std::string Sha256(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr);
  return std::string(reinterpret_cast<const char*>(digest), size);
}

}  // namespace

std::string DefaultModelName(const std::string& file) {
  std::string name = std::filesystem::path(file).stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  }
  return name.substr(0, 64);
}

std::string ModelFormat(const std::string& file) {
  const std::filesystem::path path(file);
  return path.extension().string().substr(path.has_extension() ? 1 : 0);
}

grpc::Status UploadModelBytes(pb::SceneService::Stub& stub, const std::string& bytes,
                              const std::string& name, const std::string& format,
                              size_t chunk_bytes, double timeout_s,
                              pb::UploadModelResponse* response) {
  grpc::ClientContext context;
  const double seconds = timeout_s + static_cast<double>(bytes.size()) / 16e6;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6)));
  auto writer = stub.UploadModel(&context, response);
  pb::UploadModelChunk chunk;
  pb::UploadModelChunk::Header* header = chunk.mutable_header();
  header->set_name(name);
  header->set_format(format);
  header->set_size_bytes(static_cast<int64_t>(bytes.size()));
  header->set_sha256(Sha256(bytes));
  size_t offset = 0;
  do {
    const size_t size = std::min(bytes.size() - offset, chunk_bytes);
    chunk.set_data(bytes.substr(offset, size));
    offset += size;
    if (!writer->Write(chunk)) break;  // the server ended the call; Finish says why
    chunk.clear_header();
  } while (offset < bytes.size());
  writer->WritesDone();
  return writer->Finish();
}

}  // namespace hs::cli
