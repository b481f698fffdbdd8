#pragma once
// haptics.v1.SceneService on the gRPC callback API: scenes and their
// objects, and model uploads. Each request runs as an edit of the scene's
// spec through the SceneRegistry, once AccessPolicy allows it; no exception
// leaves a handler.

#include "haptics/v1/scene_service.grpc.pb.h"
#include "server/auth/access_policy.h"
#include "server/scene_registry.h"

namespace hs {

class SceneServiceImpl final : public haptics::v1::SceneService::CallbackService {
 public:
  /// `registry` and `access` outlive the service.
  SceneServiceImpl(SceneRegistry& registry, const AccessPolicy& access)
      : registry_(registry), access_(access) {}

  grpc::ServerUnaryReactor* CreateScene(grpc::CallbackServerContext* context,
                                        const haptics::v1::CreateSceneRequest* request,
                                        haptics::v1::SceneInfo* response) override;
  grpc::ServerUnaryReactor* GetScene(grpc::CallbackServerContext* context,
                                     const haptics::v1::GetSceneRequest* request,
                                     haptics::v1::SceneInfo* response) override;
  grpc::ServerUnaryReactor* ListScenes(grpc::CallbackServerContext* context,
                                       const haptics::v1::ListScenesRequest* request,
                                       haptics::v1::ListScenesResponse* response) override;
  grpc::ServerUnaryReactor* DeleteScene(grpc::CallbackServerContext* context,
                                        const haptics::v1::DeleteSceneRequest* request,
                                        haptics::v1::DeleteSceneResponse* response) override;
  grpc::ServerReadReactor<haptics::v1::UploadModelChunk>* UploadModel(
      grpc::CallbackServerContext* context, haptics::v1::UploadModelResponse* response) override;
  grpc::ServerUnaryReactor* AddObject(grpc::CallbackServerContext* context,
                                      const haptics::v1::AddObjectRequest* request,
                                      haptics::v1::SceneInfo* response) override;
  grpc::ServerUnaryReactor* UpdateObject(grpc::CallbackServerContext* context,
                                         const haptics::v1::UpdateObjectRequest* request,
                                         haptics::v1::SceneInfo* response) override;
  grpc::ServerUnaryReactor* RemoveObject(grpc::CallbackServerContext* context,
                                         const haptics::v1::RemoveObjectRequest* request,
                                         haptics::v1::SceneInfo* response) override;
  grpc::ServerUnaryReactor* SetEffects(grpc::CallbackServerContext* context,
                                       const haptics::v1::SetEffectsRequest* request,
                                       haptics::v1::SceneInfo* response) override;

 private:
  SceneRegistry& registry_;
  const AccessPolicy& access_;
};

}  // namespace hs
