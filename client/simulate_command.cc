#include "client/simulate_command.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <utility>

#include "client/contact_json.h"
#include "client/exit_codes.h"
#include "client/needs_args.h"
#include "client/tool_path.h"
#include "common/api/scene_file.h"
#include "common/core/status_macros.h"

namespace hs::cli {
namespace {

nlohmann::ordered_json FrameJson(const StepFrame& frame, const LoadedScene& loaded) {
  nlohmann::ordered_json tools = nlohmann::ordered_json::array();
  for (const ToolFrame& t : frame.tools) {
    nlohmann::ordered_json contacts = nlohmann::ordered_json::array();
    for (const PairContact& c : t.contacts) {
      nlohmann::ordered_json entry = ContactSetToJson(c.contact);
      entry["object"] = loaded.names[c.object];
      entry["substep"] = c.substep;
      contacts.push_back(std::move(entry));
    }
    tools.push_back({{"tool", loaded.names[t.tool]},
                     {"device_position_W_m", Vector3Json(t.X_WD.translation())},
                     {"proxy_position_W_m", Vector3Json(t.X_WP.translation())},
                     {"force_W_n", Vector3Json(t.force_W)},
                     {"torque_W_nm", Vector3Json(t.torque_W)},
                     {"force_clamped", t.force_clamped},
                     {"substeps", t.substeps},
                     {"contacts", contacts}});
  }
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  for (std::string_view name : EffectNames(frame.stages_run)) stages.push_back(name);
  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (const BodyFrame& b : frame.bodies) {
    const Eigen::Quaterniond q(b.X_WO.linear());
    bodies.push_back({{"body", loaded.names[b.body]},
                      {"position_W_m", Vector3Json(b.X_WO.translation())},
                      {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                      {"velocity_W_m_per_s", Vector3Json(b.v_W)},
                      {"angular_velocity_W_rad_per_s", Vector3Json(b.w_W)},
                      {"contacts", b.contacts},
                      {"substeps", b.substeps}});
  }
  return {{"step", frame.step},
          {"time_s", frame.time_s},
          {"stages_run", stages},
          {"tools", tools},
          {"bodies", bodies}};
}

// A tool and the device poses it is driven along, one per step.
struct DrivenTool {
  ObjectId tool = -1;
  std::vector<Isometry3d> poses;
};

// The tool an entry of --tool-path drives, and its file: "TOOL=FILE" when
// TOOL names an object of the scene, else the whole entry is the first
// tool's file.
absl::StatusOr<std::pair<ObjectId, std::string>> ToolAndFile(const LoadedScene& scene,
                                                             const std::string& entry) {
  const size_t equals = entry.find('=');
  if (equals != std::string::npos) {
    const std::string name = entry.substr(0, equals);
    if (const ObjectId tool = FindTool(scene, name); tool >= 0) {
      return std::make_pair(tool, entry.substr(equals + 1));
    }
    if (std::find(scene.names.begin(), scene.names.end(), name) != scene.names.end()) {
      return absl::InvalidArgumentError("--tool-path " + entry + ": '" + name + "' is not a tool");
    }
    if (!std::filesystem::exists(entry)) {
      return absl::InvalidArgumentError("--tool-path " + entry + ": no tool named '" + name + "'");
    }
  }
  if (scene.tools.empty()) {
    return absl::FailedPreconditionError("a tool path was given but the scene has no tool");
  }
  return std::make_pair(scene.tools.front(), entry);
}

absl::StatusOr<std::vector<DrivenTool>> ReadToolPaths(const LoadedScene& scene,
                                                      const std::vector<std::string>& entries) {
  std::vector<DrivenTool> driven;
  for (const std::string& entry : entries) {
    HS_ASSIGN_OR_RETURN(const auto tool_and_file, ToolAndFile(scene, entry));
    const auto& [tool, file] = tool_and_file;
    for (const DrivenTool& d : driven) {
      if (d.tool == tool) {
        return absl::InvalidArgumentError("--tool-path: tool '" + scene.names[tool] +
                                          "' has two paths");
      }
    }
    HS_ASSIGN_OR_RETURN(std::vector<Isometry3d> poses, ReadToolPath(file));
    driven.push_back({tool, std::move(poses)});
  }
  return driven;
}

nlohmann::ordered_json StatsJson(const StageStatsTable& stats) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int i = 0; i < kNumEffects; ++i) {
    out[std::string(EffectName(static_cast<Effect>(i)))] = {
        {"runs", stats[i].runs},
        {"mean_us", stats[i].runs ? 1e-3 * stats[i].total_ns / stats[i].runs : 0.0}};
  }
  return out;
}

}  // namespace

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  auto fail = [&](const absl::Status& status) {
    err << "hapticctl simulate: " << status.message() << "\n";
    return kExitFailure;
  };
  absl::StatusOr<LoadedScene> loaded = LoadSceneFile(args.scene_file);
  if (!loaded.ok()) return fail(loaded.status());
  absl::StatusOr<std::vector<DrivenTool>> driven = ReadToolPaths(*loaded, args.tool_paths);
  if (!driven.ok()) return fail(driven.status());
  absl::StatusOr<EffectSet> needs = ParseNeeds(args.needs);
  if (!needs.ok()) return fail(needs.status());
  Scene& scene = *loaded->scene;
  scene.SetNeeded(*needs);
  for (int step = 0; step < args.steps; ++step) {
    for (const DrivenTool& d : *driven) {
      if (step >= static_cast<int>(d.poses.size())) continue;
      if (absl::Status s = scene.SetDevicePose(d.tool, d.poses[step]); !s.ok()) return fail(s);
    }
    const StepFrame& frame = scene.Step();
    if (args.json) {
      out << FrameJson(frame, *loaded).dump() << "\n";
      continue;
    }
    out << "step " << frame.step;
    for (const ToolFrame& t : frame.tools) {
      out << "  " << loaded->names[t.tool] << ": contacts " << t.contacts.size() << ", force "
          << t.force_W.transpose() << " N";
    }
    for (const BodyFrame& b : frame.bodies) {
      out << "  " << loaded->names[b.body] << ": at " << b.X_WO.translation().transpose()
          << " m, contacts " << b.contacts;
    }
    out << "\n";
  }
  if (args.json) {
    out << nlohmann::ordered_json{{"stage_stats", StatsJson(scene.stats())}}.dump() << "\n";
  } else {
    const nlohmann::ordered_json stats = StatsJson(scene.stats());
    for (const auto& [name, s] : stats.items()) {
      out << name << ": " << s["runs"] << " runs, " << s["mean_us"] << " us mean\n";
    }
  }
  return kExitOk;
}

void AddSimulateCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand("simulate", "Run a scene file offline and print each step");
  cmd->add_option("scene", args->scene_file, "Scene file (protobuf text format, or .json)")
      ->required();
  cmd->add_option("--steps", args->steps, "Number of steps")->check(CLI::Range(0, 10000000));
  cmd->add_option("--tool-path", args->tool_paths,
                  "[TOOL=]FILE: device poses of TOOL (default: the first tool), one "
                  "'x,y,z,rx,ry,rz' line per step; once per tool")
      ->allow_extra_args(false);
  AddNeedsOption(*cmd, args->needs);
  cmd->add_flag("--json", args->json, "One JSON object per step, then the stage statistics");
  cmd->callback([args, &exit_code] { exit_code = RunSimulate(*args, std::cout, std::cerr); });
}

}  // namespace hs::cli
