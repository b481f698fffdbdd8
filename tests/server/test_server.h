#pragma once
// An in-process haptic-server on a free 127.0.0.1 port for the server tests,
// with stubs and a small scene, stopped when the fixture goes.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"
#include "server/haptic_server.h"

namespace hs::testing {

namespace pb = haptics::v1;

/// A fixed 0.2 m x 0.2 m x 0.02 m box "table" centred at the origin and a
/// 0.02 m cube tool "probe" 0.05 m above it, at 1 kHz. With
/// `second_tool`, another cube tool "stylus" beside the probe.
pb::SceneSpec SmallScene(const std::string& name, bool second_tool = false);

/// A pose at (x, y, z), metres, world frame, no rotation.
pb::Pose PoseAt(double x, double y, double z);

class TestServer {
 public:
  /// Records sessions when `recording.dir` is set.
  explicit TestServer(const ServerLimits& limits = {}, const RecordingOptions& recording = {});
  ~TestServer();

  HapticServer& server() { return *server_; }
  Metrics& metrics() { return metrics_; }
  std::string address() const;
  pb::SceneService::Stub& scenes() { return *scenes_; }
  pb::SessionService::Stub& sessions() { return *sessions_; }
  std::shared_ptr<grpc::Channel> channel() { return channel_; }

  /// CreateScene through the API; fails the test when it fails.
  void Create(const pb::SceneSpec& spec);
  /// GetScene; fails the test when it fails.
  pb::SceneInfo Get(const std::string& scene);

 private:
  Metrics metrics_;
  std::unique_ptr<HapticServer> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<pb::SceneService::Stub> scenes_;
  std::unique_ptr<pb::SessionService::Stub> sessions_;
};

/// A client context whose call gives up after `seconds`.
std::unique_ptr<grpc::ClientContext> ContextWithin(double seconds);

using DeviceStream = grpc::ClientReaderWriter<pb::InteractRequest, pb::Frame>;
/// An Interact stream on `context` that has asked for `tool` of `scene`
/// (null, failing the test, when the request cannot be written).
std::unique_ptr<DeviceStream> OpenDevice(pb::SessionService::Stub& stub,
                                         grpc::ClientContext& context, const std::string& scene,
                                         const std::string& tool);

/// UploadModel through `stub`: `data` in chunks of `chunk_bytes`, the
/// header (name, format, size, `sha256`) on the first.
grpc::Status UploadModel(pb::SceneService::Stub& stub, const std::string& name,
                         const std::string& format, const std::string& data,
                         const std::string& sha256, size_t chunk_bytes,
                         pb::UploadModelResponse* response);

}  // namespace hs::testing
