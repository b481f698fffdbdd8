#pragma once
// SceneService.UploadModel from bytes in memory: the header (name, format,
// size, SHA-256) on the first chunk, then the bytes in chunks. Shared by
// `hapticctl upload` and the client SDK.

#include <grpcpp/grpcpp.h>

#include <cstddef>
#include <string>

#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {

/// The model name of `file` when none is given: its name without the
/// extension, characters outside [A-Za-z0-9_.-] replaced by '_', at most 64.
std::string DefaultModelName(const std::string& file);
/// The format of `file`: its extension without the dot ("obj"); empty for none.
std::string ModelFormat(const std::string& file);

/// Uploads `bytes` as model `name` of `format` ("obj", "stl", ...) in
/// chunks of `chunk_bytes`; the call's deadline is `timeout_s` plus 1 s
/// per 16 MB (large files take longer than one request).
grpc::Status UploadModelBytes(haptics::v1::SceneService::Stub& stub, const std::string& bytes,
                              const std::string& name, const std::string& format,
                              size_t chunk_bytes, double timeout_s,
                              haptics::v1::UploadModelResponse* response);

}  // namespace hs::cli
