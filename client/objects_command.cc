#include "client/objects_command.h"

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/json_util.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "client/channel.h"
#include "client/exit_codes.h"
#include "client/pose_args.h"
#include "client/scenes_command.h"
#include "common/api/proto_convert.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

absl::StatusOr<pb::SceneObject> ReadObjectFile(const std::string& file) {
  std::ifstream in(file);
  if (!in) return absl::NotFoundError(file + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  pb::SceneObject object;
  const bool parsed = absl::EndsWith(file, ".json")
                          ? google::protobuf::util::JsonStringToMessage(text.str(), &object).ok()
                          : google::protobuf::TextFormat::ParseFromString(text.str(), &object);
  if (!parsed) return absl::InvalidArgumentError(file + ": not a haptics.v1.SceneObject");
  return object;
}

// The object `args` describes for AddObject.
absl::StatusOr<pb::SceneObject> NewObject(const ObjectsArgs& args) {
  pb::SceneObject object;
  if (!args.object_file.empty()) {
    absl::StatusOr<pb::SceneObject> read = ReadObjectFile(args.object_file);
    if (!read.ok()) return read.status();
    object = *std::move(read);
  } else {
    object.set_kind(args.kind == "tool"   ? pb::OBJECT_KIND_TOOL
                    : args.kind == "free" ? pb::OBJECT_KIND_FREE
                                          : pb::OBJECT_KIND_FIXED);
    pb::ModelSource* model = object.mutable_model();
    if (!args.box.empty()) {
      absl::StatusOr<Vector3d> size = ParseVector3(args.box);
      if (!size.ok()) return size.status();
      VectorToProto(*size, model->mutable_procedural()->mutable_box()->mutable_size_m());
    } else if (args.sphere_radius_m > 0) {
      pb::Procedural::Sphere* sphere = model->mutable_procedural()->mutable_sphere();
      sphere->set_radius_m(args.sphere_radius_m);
      sphere->set_subdivisions(3);
    } else if (!args.model_id.empty()) {
      model->set_uploaded_model_id(args.model_id);
    } else {
      return absl::InvalidArgumentError("give a shape: --box, --sphere, --model or --from");
    }
  }
  if (!args.object.empty()) object.set_name(args.object);
  if (!args.pose.empty()) {
    absl::StatusOr<Isometry3d> pose = ParsePose(args.pose);
    if (!pose.ok()) return pose.status();
    PoseToProto(*pose, object.mutable_pose());
  }
  return object;
}

// The UpdateObject request `args` describes.
absl::StatusOr<pb::UpdateObjectRequest> UpdateRequest(const ObjectsArgs& args) {
  pb::UpdateObjectRequest request;
  request.set_scene(args.scene);
  request.set_object(args.object);
  if (!args.pose.empty()) {
    absl::StatusOr<Isometry3d> pose = ParsePose(args.pose);
    if (!pose.ok()) return pose.status();
    PoseToProto(*pose, request.mutable_pose());
  }
  if (!args.material.empty()) {
    absl::StatusOr<std::vector<double>> m = ParseNumbers(args.material, 4);
    if (!m.ok()) return m.status();
    request.set_set_materials(true);
    pb::MaterialOverride* override = request.add_materials();
    override->set_face_group(args.face_group);
    override->mutable_material()->set_stiffness_n_per_m((*m)[0]);
    override->mutable_material()->set_damping_ns_per_m((*m)[1]);
    override->mutable_material()->set_static_friction((*m)[2]);
    override->mutable_material()->set_dynamic_friction((*m)[3]);
  }
  for (const std::string& text : args.vertex_moves) {
    absl::StatusOr<std::pair<int, Vector3d>> move = ParseVertexMove(text);
    if (!move.ok()) return move.status();
    const auto& [id, p] = *move;
    pb::VertexMove* vertex = request.add_vertex_moves();
    vertex->set_vertex_id(id);
    VectorToProto(p, vertex->mutable_position_m());
  }
  return request;
}

}  // namespace

int RunObjects(const ObjectsArgs& args, std::ostream& out, std::ostream& err) {
  const std::string command = "objects " + args.action;
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError(command, channel.status(), err);
  auto stub = pb::SceneService::NewStub(*channel);
  auto context = ContextWithin(args.server.timeout_s);
  pb::SceneInfo info;
  grpc::Status status;
  if (args.action == "add") {
    absl::StatusOr<pb::SceneObject> object = NewObject(args);
    if (!object.ok()) return ReportError(command, object.status(), err);
    pb::AddObjectRequest request;
    request.set_scene(args.scene);
    *request.mutable_object() = *std::move(object);
    status = stub->AddObject(context.get(), request, &info);
  } else if (args.action == "update") {
    absl::StatusOr<pb::UpdateObjectRequest> request = UpdateRequest(args);
    if (!request.ok()) return ReportError(command, request.status(), err);
    status = stub->UpdateObject(context.get(), *request, &info);
  } else if (args.action == "remove") {
    pb::RemoveObjectRequest request;
    request.set_scene(args.scene);
    request.set_object(args.object);
    status = stub->RemoveObject(context.get(), request, &info);
  } else {
    return ReportError("objects", "unknown action " + args.action, err);
  }
  if (!status.ok()) return ReportRpcError(command, status, err);
  PrintSceneInfo(info, args.json, true, out);
  return kExitOk;
}

void AddObjectsCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ObjectsArgs>();
  CLI::App* objects = app.add_subcommand("objects", "Add, change and remove a scene's objects");
  objects->require_subcommand(1);
  auto action = [&exit_code, args](CLI::App* cmd, const std::string& name) {
    AddConnectionOptions(*cmd, args->server);
    cmd->add_option("SCENE", args->scene, "Scene name")->required();
    cmd->add_option("OBJECT", args->object, "Object name")->required();
    cmd->add_flag("--json", args->json, "The scene's new haptics.v1.SceneInfo as JSON");
    cmd->callback([&exit_code, args, name] {
      args->action = name;
      exit_code = RunObjects(*args, std::cout, std::cerr);
    });
    return cmd;
  };
  CLI::App* add = action(objects->add_subcommand("add", "Add an object to a scene"), "add");
  add->add_option("--kind", args->kind, "fixed, tool or free (moved by the simulation)")
      ->check(CLI::IsMember({"fixed", "tool", "free"}))
      ->capture_default_str();
  add->add_option("--box", args->box, "A box: full side lengths x,y,z, metres")
      ->check(Vector3Value());
  add->add_option("--sphere", args->sphere_radius_m, "A sphere of this radius, metres")
      ->check(CLI::PositiveNumber);
  add->add_option("--model", args->model_id, "An uploaded model's id (see upload)");
  add->add_option("--from", args->object_file,
                  "A haptics.v1.SceneObject file (text format, or JSON for *.json)");
  add->add_option("--pose", args->pose, "X_WO: x,y,z,rx,ry,rz (metres, rotation vector)")
      ->check(PoseValue());
  CLI::App* update =
      action(objects->add_subcommand("update", "Change an object's pose, materials or vertices"),
             "update");
  update->add_option("--pose", args->pose, "X_WO: x,y,z,rx,ry,rz (metres, rotation vector)")
      ->check(PoseValue());
  update->add_option("--material", args->material,
                     "stiffness,damping,static,dynamic (N/m, N s/m, friction coefficients)")
      ->check(NumbersValue(4));
  update->add_option("--face-group", args->face_group,
                     "Material name the --material is for (default: every group)");
  update->add_option("--move-vertex", args->vertex_moves,
                     "ID:x,y,z, object frame, metres (repeatable)")
      ->check(VertexMoveValue());
  action(objects->add_subcommand("remove", "Remove an object from a scene"), "remove");
}

}  // namespace hs::cli
