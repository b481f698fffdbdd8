#include "client/scenes_command.h"

#include <iostream>

#include "client/channel.h"
#include "client/exit_codes.h"
#include "common/api/object_kind_name.h"
#include "common/api/scene_file.h"
#include "haptics/v1/scene_service.grpc.pb.h"

namespace hs::cli {

namespace pb = haptics::v1;

void PrintSceneInfo(const pb::SceneInfo& info, bool json, bool with_objects, std::ostream& out) {
  if (json) {
    out << ProtoToJsonLine(info) << "\n";
    return;
  }
  out << info.spec().name() << ": step " << info.step() << ", " << info.step_s() << " s/step, "
      << info.triangles() << " triangles, " << info.devices() << " device(s), " << info.viewers()
      << " viewer(s), revision " << info.revision() << "\n";
  if (!with_objects) return;
  for (const pb::SceneObject& object : info.spec().objects()) {
    const pb::Vector3& p = object.pose().position_m();
    out << "  " << object.name() << " (" << ObjectKindName(object.kind()) << ") at (" << p.x()
        << ", " << p.y() << ", " << p.z() << ") m\n";
  }
  for (const std::string& tool : info.claimed_tools())
    out << "  held by a device: " << tool << "\n";
}

int RunScenes(const ScenesArgs& args, std::ostream& out, std::ostream& err) {
  const std::string command = "scenes " + args.action;
  absl::StatusOr<std::shared_ptr<grpc::Channel>> channel = MakeChannel(args.server);
  if (!channel.ok()) return ReportError(command, channel.status(), err);
  auto stub = pb::SceneService::NewStub(*channel);
  auto context = ContextWithin(args.server.timeout_s);
  grpc::Status status;
  pb::SceneInfo info;
  if (args.action == "list") {
    pb::ListScenesResponse response;
    status = stub->ListScenes(context.get(), pb::ListScenesRequest(), &response);
    if (!status.ok()) return ReportRpcError(command, status, err);
    for (const pb::SceneInfo& scene : response.scenes()) {
      PrintSceneInfo(scene, args.json, false, out);
    }
    return kExitOk;
  }
  if (args.action == "create") {
    absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(args.scene_file);
    if (!spec.ok()) return ReportError(command, spec.status(), err);
    pb::CreateSceneRequest request;
    *request.mutable_spec() = *std::move(spec);
    if (!args.name.empty()) request.mutable_spec()->set_name(args.name);
    status = stub->CreateScene(context.get(), request, &info);
  } else if (args.action == "show") {
    pb::GetSceneRequest request;
    request.set_scene(args.name);
    status = stub->GetScene(context.get(), request, &info);
  } else if (args.action == "delete") {
    pb::DeleteSceneRequest request;
    request.set_scene(args.name);
    pb::DeleteSceneResponse response;
    status = stub->DeleteScene(context.get(), request, &response);
    if (status.ok()) out << "deleted " << args.name << "\n";
    return status.ok() ? kExitOk : ReportRpcError(command, status, err);
  } else {
    return ReportError("scenes", "unknown action " + args.action, err);
  }
  if (!status.ok()) return ReportRpcError(command, status, err);
  PrintSceneInfo(info, args.json, true, out);
  return kExitOk;
}

void AddScenesCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ScenesArgs>();
  CLI::App* scenes =
      app.add_subcommand("scenes", "List, create, show and delete a server's scenes");
  scenes->require_subcommand(1);
  auto action = [&exit_code, args](CLI::App* cmd, const std::string& name) {
    AddConnectionOptions(*cmd, args->server);
    cmd->add_flag("--json", args->json, "haptics.v1.SceneInfo as JSON, one line each");
    cmd->callback([&exit_code, args, name] {
      args->action = name;
      exit_code = RunScenes(*args, std::cout, std::cerr);
    });
    return cmd;
  };
  action(scenes->add_subcommand("list", "Every scene's name and state"), "list");
  CLI::App* create = action(
      scenes->add_subcommand("create", "Create a scene from a scene file and start stepping it"),
      "create");
  create->add_option("SCENE_FILE", args->scene_file, "haptics.v1.SceneSpec, text format or JSON")
      ->required();
  create->add_option("--name", args->name, "Scene name (default: the file's)");
  action(scenes->add_subcommand("show", "A scene's state and objects"), "show")
      ->add_option("NAME", args->name, "Scene name")
      ->required();
  action(scenes->add_subcommand("delete", "Stop a scene; its streams end"), "delete")
      ->add_option("NAME", args->name, "Scene name")
      ->required();
}

}  // namespace hs::cli
