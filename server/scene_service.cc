#include "server/scene_service.h"

#include <exception>

#include "absl/strings/str_cat.h"
#include "common/core/status_macros.h"
#include "server/grpc_status.h"
#include "server/raw_message.h"
#include "server/spec_edit.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// Runs `handler` and ends the call with its status; counts failures and
// keeps exceptions inside.
template <class Handler>
absl::Status Guarded(Metrics& metrics, const char* method, Handler&& handler) {
  absl::Status status;
  try {
    status = handler();
  } catch (const std::exception& e) {
    status = absl::InternalError(e.what());
  } catch (...) {
    status = absl::InternalError("unknown exception");
  }
  if (!status.ok()) metrics.AddRejected(method, absl::StatusCodeToString(status.code()));
  return status;
}

// Parses the request, runs `handler(&request, &response)` and serializes
// the response; ends the call with the first error.
template <class Request, class Response, class Handler>
grpc::ServerUnaryReactor* Respond(grpc::CallbackServerContext* context, Metrics& metrics,
                                  const char* method, const grpc::ByteBuffer* raw_request,
                                  grpc::ByteBuffer* raw_response, Handler&& handler) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  Request request;
  Response response;
  reactor->Finish(ToGrpcStatus(Guarded(metrics, method, [&]() -> absl::Status {
    HS_RETURN_IF_ERROR(ParseMessage(*raw_request, request));
    HS_RETURN_IF_ERROR(handler(&request, &response));
    return SerializeMessage(response, *raw_response);
  })));
  return reactor;
}

void InfoToProto(const RunnerInfo& info, double step_s, pb::SceneInfo* out) {
  *out->mutable_spec() = info.spec;
  out->set_step(info.step);
  out->set_step_s(step_s);
  out->set_triangles(info.triangles);
  out->set_devices(info.devices);
  out->set_viewers(info.viewers);
  for (const std::string& tool : info.claimed_tools) out->add_claimed_tools(tool);
  out->set_revision(info.revision);
}

// Edits scene `name` and answers with its new state.
absl::Status EditAndAnswer(SceneRegistry& registry, grpc::CallbackServerContext* context,
                           const std::string& name, const SceneRegistry::SpecEdit& edit,
                           pb::SceneInfo* response) {
  absl::StatusOr<RunnerInfo> info = registry.Edit(name, edit, context->deadline());
  if (!info.ok()) return info.status();
  absl::StatusOr<std::shared_ptr<SceneRunner>> runner = registry.Find(name);
  InfoToProto(*info, runner.ok() ? (*runner)->step_s() : 0, response);
  return absl::OkStatus();
}

class UploadReactor : public grpc::ServerReadReactor<pb::UploadModelChunk> {
 public:
  // Reads the upload of `caller` when it may upload, else ends the call
  // with the error.
  UploadReactor(SceneRegistry& registry, const absl::StatusOr<Caller>& caller,
                pb::UploadModelResponse* response)
      : registry_(registry), response_(response), upload_(registry.limits().max_model_bytes) {
    absl::Status allowed = caller.status();
    if (allowed.ok()) allowed = registry_.quotas().Take(caller->id, Quota::kUploadsInFlight);
    if (!allowed.ok()) {
      registry_.metrics().AddRejected("UploadModel", absl::StatusCodeToString(allowed.code()));
      Finish(ToGrpcStatus(allowed));
      return;
    }
    caller_ = caller->id;
    StartRead(&chunk_);
  }

  void OnReadDone(bool ok) override {
    absl::Status status = Guarded(registry_.metrics(), "UploadModel", [&] {
      if (!ok) return Store();
      return upload_.Add(chunk_);
    });
    if (ok && status.ok()) {
      StartRead(&chunk_);
      return;
    }
    Finish(ToGrpcStatus(status));
  }
  void OnDone() override {
    if (!caller_.empty()) registry_.quotas().Give(caller_, Quota::kUploadsInFlight);
    delete this;
  }

 private:
  absl::Status Store() {
    HS_RETURN_IF_ERROR(registry_.quotas().Take(caller_, Quota::kModels));
    absl::StatusOr<StoredModel> stored = registry_.models().Store(upload_);
    if (!stored.ok() || stored->existed) registry_.quotas().Give(caller_, Quota::kModels);
    if (!stored.ok()) return stored.status();
    if (!stored->existed) registry_.quotas().Own(caller_, Quota::kModels, stored->model_id);
    response_->set_model_id(stored->model_id);
    response_->set_vertices(stored->vertices);
    response_->set_triangles(stored->triangles);
    return absl::OkStatus();
  }

  SceneRegistry& registry_;
  pb::UploadModelResponse* response_;
  ModelUpload upload_;
  pb::UploadModelChunk chunk_;
  std::string caller_;  // set once it may upload
};

}  // namespace

grpc::ServerUnaryReactor* SceneServiceImpl::CreateScene(grpc::CallbackServerContext* context,
                                                        const grpc::ByteBuffer* raw_request,
                                                        grpc::ByteBuffer* raw_response) {
  return Respond<pb::CreateSceneRequest, pb::SceneInfo>(
      context, registry_.metrics(), "CreateScene", raw_request, raw_response,
      [&](const pb::CreateSceneRequest* request, pb::SceneInfo* response) -> absl::Status {
        absl::StatusOr<Caller> caller =
            access_.Check(*context, Access::kAdmin, request->spec().name());
        if (!caller.ok()) return caller.status();
        if (absl::Status s = RejectModelPaths(request->spec()); !s.ok()) return s;
        HS_RETURN_IF_ERROR(registry_.quotas().Take(caller->id, Quota::kScenes));
        absl::StatusOr<RunnerInfo> info =
            registry_.Create(request->spec(), "", context->deadline());
        if (!info.ok()) {
          registry_.quotas().Give(caller->id, Quota::kScenes);
          return info.status();
        }
        registry_.quotas().Own(caller->id, Quota::kScenes, request->spec().name());
        absl::StatusOr<std::shared_ptr<SceneRunner>> runner =
            registry_.Find(request->spec().name());
        InfoToProto(*info, runner.ok() ? (*runner)->step_s() : 0, response);
        return absl::OkStatus();
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::GetScene(grpc::CallbackServerContext* context,
                                                     const grpc::ByteBuffer* raw_request,
                                                     grpc::ByteBuffer* raw_response) {
  return Respond<pb::GetSceneRequest, pb::SceneInfo>(
      context, registry_.metrics(), "GetScene", raw_request, raw_response,
      [&](const pb::GetSceneRequest* request, pb::SceneInfo* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kRead, request->scene()).status());
        absl::StatusOr<std::shared_ptr<SceneRunner>> runner = registry_.Find(request->scene());
        if (!runner.ok()) return runner.status();
        InfoToProto((*runner)->Info(), (*runner)->step_s(), response);
        return absl::OkStatus();
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::GetGeometry(grpc::CallbackServerContext* context,
                                                        const grpc::ByteBuffer* raw_request,
                                                        grpc::ByteBuffer* raw_response) {
  return Respond<pb::GetGeometryRequest, pb::SceneGeometry>(
      context, registry_.metrics(), "GetGeometry", raw_request, raw_response,
      [&](const pb::GetGeometryRequest* request, pb::SceneGeometry* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kRead, request->scene()).status());
        absl::StatusOr<std::shared_ptr<SceneRunner>> runner = registry_.Find(request->scene());
        if (!runner.ok()) return runner.status();
        (*runner)->Geometry(response);
        return absl::OkStatus();
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::ListScenes(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* raw_request,
                                                       grpc::ByteBuffer* raw_response) {
  return Respond<pb::ListScenesRequest, pb::ListScenesResponse>(
      context, registry_.metrics(), "ListScenes", raw_request, raw_response,
      [&](const pb::ListScenesRequest*, pb::ListScenesResponse* response) -> absl::Status {
        absl::StatusOr<Caller> caller = access_.Check(*context, Access::kRead, "");
        if (!caller.ok()) return caller.status();
        for (const std::shared_ptr<SceneRunner>& runner : registry_.List()) {
          RunnerInfo info = runner->Info();
          const std::string name = info.spec.name();
          if (!AccessPolicy::MaySee(*caller, name)) continue;
          info.spec.Clear();
          info.spec.set_name(name);
          InfoToProto(info, runner->step_s(), response->add_scenes());
        }
        return absl::OkStatus();
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::DeleteScene(grpc::CallbackServerContext* context,
                                                        const grpc::ByteBuffer* raw_request,
                                                        grpc::ByteBuffer* raw_response) {
  return Respond<pb::DeleteSceneRequest, pb::DeleteSceneResponse>(
      context, registry_.metrics(), "DeleteScene", raw_request, raw_response,
      [&](const pb::DeleteSceneRequest* request, pb::DeleteSceneResponse*) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, request->scene()).status());
        HS_RETURN_IF_ERROR(registry_.Delete(request->scene()));
        registry_.quotas().Disown(Quota::kScenes, request->scene());
        return absl::OkStatus();
      });
}

grpc::ServerReadReactor<pb::UploadModelChunk>* SceneServiceImpl::UploadModel(
    grpc::CallbackServerContext* context, pb::UploadModelResponse* response) {
  return new UploadReactor(registry_, access_.Check(*context, Access::kAdmin, ""), response);
}

grpc::ServerUnaryReactor* SceneServiceImpl::DeleteModel(grpc::CallbackServerContext* context,
                                                        const grpc::ByteBuffer* raw_request,
                                                        grpc::ByteBuffer* raw_response) {
  return Respond<pb::DeleteModelRequest, pb::DeleteModelResponse>(
      context, registry_.metrics(), "DeleteModel", raw_request, raw_response,
      [&](const pb::DeleteModelRequest* request, pb::DeleteModelResponse*) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, "").status());
        HS_RETURN_IF_ERROR(registry_.DeleteModel(request->model_id()));
        registry_.quotas().Disown(Quota::kModels, request->model_id());
        return absl::OkStatus();
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::AddObject(grpc::CallbackServerContext* context,
                                                      const grpc::ByteBuffer* raw_request,
                                                      grpc::ByteBuffer* raw_response) {
  return Respond<pb::AddObjectRequest, pb::SceneInfo>(
      context, registry_.metrics(), "AddObject", raw_request, raw_response,
      [&](const pb::AddObjectRequest* request, pb::SceneInfo* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, request->scene()).status());
        pb::SceneSpec alone;
        *alone.add_objects() = request->object();
        if (absl::Status s = RejectModelPaths(alone); !s.ok()) return s;
        return EditAndAnswer(
            registry_, context, request->scene(),
            [&](pb::SceneSpec& spec) { return AddObjectToSpec(request->object(), spec); },
            response);
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::UpdateObject(grpc::CallbackServerContext* context,
                                                         const grpc::ByteBuffer* raw_request,
                                                         grpc::ByteBuffer* raw_response) {
  return Respond<pb::UpdateObjectRequest, pb::SceneInfo>(
      context, registry_.metrics(), "UpdateObject", raw_request, raw_response,
      [&](const pb::UpdateObjectRequest* request, pb::SceneInfo* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, request->scene()).status());
        if (request->vertex_moves_size() > registry_.limits().max_vertex_moves_per_request) {
          return absl::ResourceExhaustedError(
              absl::StrCat(request->vertex_moves_size(), " vertex moves; at most ",
                           registry_.limits().max_vertex_moves_per_request, " per request"));
        }
        return EditAndAnswer(
            registry_, context, request->scene(),
            [&](pb::SceneSpec& spec) { return UpdateObjectInSpec(*request, spec); }, response);
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::RemoveObject(grpc::CallbackServerContext* context,
                                                         const grpc::ByteBuffer* raw_request,
                                                         grpc::ByteBuffer* raw_response) {
  return Respond<pb::RemoveObjectRequest, pb::SceneInfo>(
      context, registry_.metrics(), "RemoveObject", raw_request, raw_response,
      [&](const pb::RemoveObjectRequest* request, pb::SceneInfo* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, request->scene()).status());
        return EditAndAnswer(
            registry_, context, request->scene(),
            [&](pb::SceneSpec& spec) { return RemoveObjectFromSpec(request->object(), spec); },
            response);
      });
}

grpc::ServerUnaryReactor* SceneServiceImpl::SetEffects(grpc::CallbackServerContext* context,
                                                       const grpc::ByteBuffer* raw_request,
                                                       grpc::ByteBuffer* raw_response) {
  return Respond<pb::SetEffectsRequest, pb::SceneInfo>(
      context, registry_.metrics(), "SetEffects", raw_request, raw_response,
      [&](const pb::SetEffectsRequest* request, pb::SceneInfo* response) -> absl::Status {
        HS_RETURN_IF_ERROR(access_.Check(*context, Access::kAdmin, request->scene()).status());
        return EditAndAnswer(
            registry_, context, request->scene(),
            [&](pb::SceneSpec& spec) {
              SetEffectsInSpec(*request, spec);
              return absl::OkStatus();
            },
            response);
      });
}

}  // namespace hs
