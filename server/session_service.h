#pragma once
// haptics.v1.SessionService on the gRPC callback API: one self-owned
// reactor per stream. Interact (devices) is latest-wins; Watch (viewers)
// has a bounded queue. The scene thread only hands frames over; writing
// happens as each client reads, so a slow client never slows the scene.

#include "haptics/v1/session_service.grpc.pb.h"
#include "server/auth/access_policy.h"
#include "server/scene_registry.h"

namespace hs {

/// Frames a viewer may have waiting before the oldest is dropped.
inline constexpr size_t kViewerQueueFrames = 64;

class SessionServiceImpl final : public haptics::v1::SessionService::CallbackService {
 public:
  /// `registry` and `access` outlive the service.
  SessionServiceImpl(SceneRegistry& registry, const AccessPolicy& access)
      : registry_(registry), access_(access) {}

  grpc::ServerBidiReactor<haptics::v1::InteractRequest, haptics::v1::Frame>* Interact(
      grpc::CallbackServerContext* context) override;
  grpc::ServerWriteReactor<haptics::v1::Frame>* Watch(
      grpc::CallbackServerContext* context, const haptics::v1::WatchRequest* request) override;

 private:
  SceneRegistry& registry_;
  const AccessPolicy& access_;
};

}  // namespace hs
