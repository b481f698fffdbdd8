#include "tests/common/recording/recorded_run.h"

#include <algorithm>
#include <optional>

#include "common/api/scene_file.h"
#include "common/core/check.h"
#include "common/recording/record_file.h"
#include "common/recording/recorded_step.h"
#include "google/protobuf/text_format.h"

namespace hs::testing_recording {
namespace {

namespace pb = haptics::v1;

constexpr char kSpec[] = R"pb(
  name: "press"
  step_s: 0.001
  objects {
    name: "table"
    kind: OBJECT_KIND_FIXED
    model { procedural { box { size_m { x: 0.5 y: 0.5 z: 0.05 } } } }
    pose { position_m { z: -0.025 } }
  }
  objects {
    name: "probe"
    kind: OBJECT_KIND_TOOL
    model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } }
    pose { position_m { z: 0.012 } }
  }
)pb";

// Every effect but the local model, as a device asks by default.
constexpr EffectSet kNeeds = EffectSet::Default();

LoadedScene Build(const pb::SceneSpec& spec) {
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, BuildPaths{});
  HS_CHECK(loaded.ok());
  return *std::move(loaded);
}

}  // namespace

std::vector<pb::Record> RecordRun(const RunOptions& options) {
  pb::SceneSpec spec;
  HS_CHECK(google::protobuf::TextFormat::ParseFromString(kSpec, &spec));
  std::vector<pb::Record> records;
  pb::RecordingStart* start = records.emplace_back().mutable_start();
  start->set_scene(spec.name());
  *start->mutable_spec() = spec;
  start->set_start_unix_ns(kStartUnixNs);
  start->set_frames(options.frames);
  start->set_step_s(spec.step_s());
  LoadedScene loaded = Build(spec);
  std::optional<Isometry3d> device;
  for (int step = 1; step <= options.steps; ++step) {
    if (step - 1 == options.edit_after && options.edit_after > 0) {
      spec.mutable_objects(0)->mutable_pose()->mutable_position_m()->set_z(-0.026);
      pb::SceneEdit* edit = records.emplace_back().mutable_edit();
      edit->set_after_step(step - 1);
      *edit->mutable_spec() = spec;
      edit->set_revision(1);
      // A rebuilt scene keeps the tool's device pose (SceneRunner::Replace).
      loaded = Build(spec);
      HS_CHECK(loaded.scene->SetDevicePose(FindTool(loaded, "probe"), *device).ok());
    }
    // 0.5 mm lower each step, from 1 cm above the table.
    Isometry3d X_WD = Isometry3d::Identity();
    X_WD.translation() = Vector3d(0.01, 0.02, 0.02 - 0.0005 * step);
    pb::DeviceInput* input = records.emplace_back().mutable_input();
    input->set_step(step);
    input->set_tool("probe");
    ExactPoseToProto(X_WD, input->mutable_device_pose());
    input->set_sequence(step);
    input->set_seat(!device.has_value());
    const ObjectId probe = FindTool(loaded, "probe");
    HS_CHECK(ApplyDevicePose(*loaded.scene, probe, X_WD, !device).ok());
    device = X_WD;
    const EffectSet needs = options.remote_device ? kNeeds.With(Effect::kLocalModel) : kNeeds;
    if (options.remote_device) {
      LocalModelRequest model = options.model;
      model.stale = std::ranges::count(options.model_stale_at, step) > 0;
      input->set_model_stale(model.stale);
      input->set_validity_radius_m(model.validity_radius_m);
      input->set_surface_only(model.surface_only);
      HS_CHECK(ApplyLocalModelRequest(*loaded.scene, probe, model).ok());
    }
    loaded.scene->SetNeeded(needs);
    const StepFrame& frame = loaded.scene->Step();
    FillRecordedFrame(step, step * spec.step_s(), frame, loaded.names, needs, options.frames,
                      records.emplace_back().mutable_frame());
  }
  pb::RecordingEnd* end = records.emplace_back().mutable_end();
  end->set_last_step(options.steps);
  end->set_end_unix_ns(kStartUnixNs + 1'000'000'000);
  return records;
}

std::string WriteRecords(const std::string& path, const std::vector<pb::Record>& records) {
  absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(path);
  HS_CHECK(writer.ok());
  for (const pb::Record& record : records) HS_CHECK(writer->Append(record).ok());
  return path;
}

}  // namespace hs::testing_recording
