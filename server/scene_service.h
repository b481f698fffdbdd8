#pragma once
// haptics.v1.SceneService on the gRPC callback API: scenes and their
// objects, and model uploads. Each request runs as an edit of the scene's
// spec through the SceneRegistry, once AccessPolicy allows it; no exception
// leaves a handler.

#include "haptics/v1/scene_service.grpc.pb.h"
#include "server/auth/access_policy.h"
#include "server/scene_registry.h"

namespace hs {

// Every unary method takes its request as bytes (raw_message.h); the
// upload stream parses its chunks as gRPC does.
using SceneServiceBase = haptics::v1::SceneService::WithRawCallbackMethod_CreateScene<
    haptics::v1::SceneService::WithRawCallbackMethod_GetScene<
        haptics::v1::SceneService::WithRawCallbackMethod_GetGeometry<
            haptics::v1::SceneService::WithRawCallbackMethod_ListScenes<
                haptics::v1::SceneService::WithRawCallbackMethod_DeleteScene<
                    haptics::v1::SceneService::WithRawCallbackMethod_AddObject<
                        haptics::v1::SceneService::WithRawCallbackMethod_UpdateObject<
                            haptics::v1::SceneService::WithRawCallbackMethod_RemoveObject<
                                haptics::v1::SceneService::WithRawCallbackMethod_SetEffects<
                                    haptics::v1::SceneService::WithRawCallbackMethod_DeleteModel<
                                        haptics::v1::SceneService::WithCallbackMethod_UploadModel<
                                            haptics::v1::SceneService::Service>>>>>>>>>>>;

class SceneServiceImpl final : public SceneServiceBase {
 public:
  /// `registry` and `access` outlive the service.
  SceneServiceImpl(SceneRegistry& registry, const AccessPolicy& access)
      : registry_(registry), access_(access) {}

  // A CreateSceneRequest, answered with a SceneInfo.
  grpc::ServerUnaryReactor* CreateScene(grpc::CallbackServerContext* context,
                                        const grpc::ByteBuffer* request,
                                        grpc::ByteBuffer* response) override;
  // A GetSceneRequest, answered with a SceneInfo.
  grpc::ServerUnaryReactor* GetScene(grpc::CallbackServerContext* context,
                                     const grpc::ByteBuffer* request,
                                     grpc::ByteBuffer* response) override;
  // A GetGeometryRequest, answered with a SceneGeometry.
  grpc::ServerUnaryReactor* GetGeometry(grpc::CallbackServerContext* context,
                                        const grpc::ByteBuffer* request,
                                        grpc::ByteBuffer* response) override;
  // A ListScenesRequest, answered with a ListScenesResponse.
  grpc::ServerUnaryReactor* ListScenes(grpc::CallbackServerContext* context,
                                       const grpc::ByteBuffer* request,
                                       grpc::ByteBuffer* response) override;
  // A DeleteSceneRequest, answered with a DeleteSceneResponse.
  grpc::ServerUnaryReactor* DeleteScene(grpc::CallbackServerContext* context,
                                        const grpc::ByteBuffer* request,
                                        grpc::ByteBuffer* response) override;
  grpc::ServerReadReactor<haptics::v1::UploadModelChunk>* UploadModel(
      grpc::CallbackServerContext* context, haptics::v1::UploadModelResponse* response) override;
  // A DeleteModelRequest, answered with a DeleteModelResponse.
  grpc::ServerUnaryReactor* DeleteModel(grpc::CallbackServerContext* context,
                                        const grpc::ByteBuffer* request,
                                        grpc::ByteBuffer* response) override;
  // AddObjectRequest, UpdateObjectRequest, RemoveObjectRequest and
  // SetEffectsRequest, each answered with a SceneInfo.
  grpc::ServerUnaryReactor* AddObject(grpc::CallbackServerContext* context,
                                      const grpc::ByteBuffer* request,
                                      grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* UpdateObject(grpc::CallbackServerContext* context,
                                         const grpc::ByteBuffer* request,
                                         grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* RemoveObject(grpc::CallbackServerContext* context,
                                         const grpc::ByteBuffer* request,
                                         grpc::ByteBuffer* response) override;
  grpc::ServerUnaryReactor* SetEffects(grpc::CallbackServerContext* context,
                                       const grpc::ByteBuffer* request,
                                       grpc::ByteBuffer* response) override;

 private:
  SceneRegistry& registry_;
  const AccessPolicy& access_;
};

}  // namespace hs
