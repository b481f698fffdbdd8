#pragma once
// haptics.v1.SessionService on the gRPC callback API: one self-owned
// reactor per stream. Interact (devices) is latest-wins; Watch (viewers)
// has a bounded queue. The scene thread only hands frames over; writing
// happens as each client reads, so a slow client never slows the scene.

#include "haptics/v1/session_service.grpc.pb.h"
#include "server/auth/access_policy.h"
#include "server/scene_registry.h"

namespace hs {

// Both methods take their requests as bytes and write frames as bytes
// (raw_message.h): a message that is no request gets INVALID_ARGUMENT.
using SessionServiceBase = haptics::v1::SessionService::WithRawCallbackMethod_Interact<
    haptics::v1::SessionService::WithRawCallbackMethod_Watch<haptics::v1::SessionService::Service>>;

class SessionServiceImpl final : public SessionServiceBase {
 public:
  /// `registry` and `access` outlive the service.
  SessionServiceImpl(SceneRegistry& registry, const AccessPolicy& access)
      : registry_(registry), access_(access) {}

  // InteractRequests in, Frames out.
  grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* Interact(
      grpc::CallbackServerContext* context) override;
  // A WatchRequest in, Frames out.
  grpc::ServerWriteReactor<grpc::ByteBuffer>* Watch(grpc::CallbackServerContext* context,
                                                    const grpc::ByteBuffer* request) override;

 private:
  SceneRegistry& registry_;
  const AccessPolicy& access_;
};

}  // namespace hs
