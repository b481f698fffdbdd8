#pragma once
// A connection to haptic-server: scenes and models, and the streams of a
// running scene (Device, Watcher). Every call may block on the network;
// none may be made from a real-time thread. A Session may be shared by
// threads; its Devices and Watchers may outlive it.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "haptics/device.h"
#include "haptics/error.h"
#include "haptics/export.h"
#include "haptics/watcher.h"

namespace haptics {

struct TlsOptions {
  /// PEM CA certificates that sign the server's; set: TLS.
  std::string ca_file;
  /// PEM client certificate and key, for a server that asks for one.
  std::string cert_file;
  std::string key_file;
  /// The name the server's certificate carries, when not the address's host.
  std::string server_name;
};

struct SessionOptions {
  TlsOptions tls;
  /// The bearer token; empty: read from token_file, else the HAPTIC_TOKEN
  /// environment variable, else none.
  std::string token;
  std::string token_file;
  /// Connect gives up after this long without reaching the server, seconds.
  double connect_timeout_s = 5;
  /// Each request's deadline, seconds.
  double call_timeout_s = 10;
};

struct SceneInfo {
  std::string name;
  int64_t step = 0;
  double step_s = 0;
  int64_t triangles = 0;
  int32_t devices = 0;
  int32_t viewers = 0;
  int64_t revision = 0;
};

struct ModelInfo {
  /// What a SceneSpec names as ModelSource.uploaded_model_id.
  std::string model_id;
  int32_t vertices = 0;
  int32_t triangles = 0;
};

class HAPTICS_EXPORT Session {
 public:
  /// Connects to `address` (host:port). UNAVAILABLE when no server answers
  /// within options.connect_timeout_s; INVALID_ARGUMENT naming a file that
  /// cannot be read.
  static Result<std::unique_ptr<Session>> Connect(const std::string& address,
                                                  const SessionOptions& options = {});
  class Impl;
  explicit Session(std::shared_ptr<Impl> impl);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// grpc.health.v1: "SERVING", "NOT_SERVING", ... of `service` (empty:
  /// the server).
  Result<std::string> Health(const std::string& service = "");
  Result<std::vector<SceneInfo>> ListScenes();
  /// Creates the scene a SceneSpec file describes (text format, or JSON for
  /// "*.json"), named `name` when given.
  Result<SceneInfo> CreateScene(const std::string& spec_file, const std::string& name = "");
  /// Deletes the scene of that name, if any, then creates it.
  Result<SceneInfo> ReplaceScene(const std::string& spec_file, const std::string& name = "");
  Error DeleteScene(const std::string& name);
  /// Uploads a model file under `name` (default: the file's stem).
  Result<ModelInfo> UploadModel(const std::string& file, const std::string& name = "");
  Error DeleteModel(const std::string& model_id);

  /// A device on `tool` of `scene`, once the server has accepted it and
  /// sent its first frame: NOT_FOUND for an unknown scene or tool,
  /// UNAUTHENTICATED or PERMISSION_DENIED for a refused token,
  /// FAILED_PRECONDITION when another device holds the tool,
  /// DEADLINE_EXCEEDED or UNAVAILABLE when the server does not answer.
  Result<std::unique_ptr<Device>> OpenDevice(const std::string& scene, const std::string& tool,
                                             const DeviceOptions& options = {});
  /// A viewer of `scene`, once its first frame came (errors as OpenDevice).
  Result<std::unique_ptr<Watcher>> Watch(const std::string& scene, WatchOptions options = {});

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace haptics
