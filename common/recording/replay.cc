#include "common/recording/replay.h"

#include <map>
#include <optional>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "common/api/scene_file.h"
#include "common/recording/recorded_step.h"
#include "google/protobuf/util/message_differencer.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// The scene as the server's SceneRunner steps it: device poses applied
// by tool name (the last one of each tool kept, as the runner keeps
// them for a rebuild), edits that rebuild the scene between steps.
class ReplayedScene {
 public:
  ReplayedScene(std::string models_dir, double step_s, pb::FrameRecording mode,
                const ReplayOptions& options)
      : models_dir_(std::move(models_dir)), step_s_(step_s), mode_(mode), options_(options) {}

  int64_t step() const { return step_; }

  absl::Status Start(const pb::RecordingStart& start) {
    step_ = start.after_step();
    return Build(start.spec(), start.after_step());
  }

  // SceneRunner::Replace: tools keep their device poses.
  absl::Status Edit(const pb::SceneEdit& edit) {
    if (edit.after_step() != step_) return OutOfOrder("an edit", edit.after_step());
    return Build(edit.spec(), step_);
  }

  // SceneRunner::StepOnce: a pose for a tool the scene lacks is skipped.
  absl::Status Input(const pb::DeviceInput& input) {
    if (input.step() != step_ + 1) return OutOfOrder("a device input", input.step());
    absl::StatusOr<Isometry3d> X_WD = ExactPoseFromProto(input.device_pose());
    if (!X_WD.ok()) return X_WD.status();
    const ObjectId id = FindTool(*loaded_, input.tool());
    if (id >= 0 && ApplyDevicePose(*loaded_->scene, id, *X_WD, input.seat()).ok()) {
      applied_[input.tool()] = *X_WD;
      const absl::Status model =
          ApplyLocalModelRequest(*loaded_->scene, id,
                                 {.stale = input.model_stale(),
                                  .validity_radius_m = input.validity_radius_m(),
                                  .surface_only = input.surface_only()});
      if (!model.ok()) {
        return absl::InvalidArgumentError(
            absl::StrCat("device input at step ", input.step(), ": ", model.message()));
      }
    }
    return absl::OkStatus();
  }

  // Steps once and returns what the recording keeps of the step.
  absl::StatusOr<const pb::RecordedFrame*> Step(const pb::RecordedFrame& recorded) {
    if (recorded.step() != step_ + 1) return OutOfOrder("a frame", recorded.step());
    absl::StatusOr<EffectSet> needs =
        EffectsFromProto(recorded.needs(), EffectSet(), absl::StrCat("frame ", recorded.step()));
    if (!needs.ok()) return needs.status();
    loaded_->scene->SetNeeded(*needs | options_.extra_needs);
    const StepFrame& frame = loaded_->scene->Step();
    ++step_;
    if (options_.on_step) {
      options_.on_step(static_cast<double>(step_) * step_s_, frame, loaded_->names);
    }
    FillRecordedFrame(step_, static_cast<double>(step_) * step_s_, frame, loaded_->names, *needs,
                      mode_, &replayed_);
    return &replayed_;
  }

 private:
  absl::Status Build(const pb::SceneSpec& spec, int64_t after_step) {
    absl::StatusOr<LoadedScene> built = BuildScene(spec, BuildPaths{"", models_dir_});
    if (!built.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(
          "the scene after step ", after_step, " does not build: ", built.status().message()));
    }
    loaded_ = std::move(*built);
    for (auto it = applied_.begin(); it != applied_.end();) {
      const ObjectId id = FindTool(*loaded_, it->first);
      it = id >= 0 && loaded_->scene->SetDevicePose(id, it->second).ok() ? std::next(it)
                                                                         : applied_.erase(it);
    }
    return absl::OkStatus();
  }

  absl::Status OutOfOrder(const std::string& what, int64_t at) const {
    return absl::InvalidArgumentError(
        absl::StrCat(what, " for step ", at, " follows step ", step_, ": records out of order"));
  }

  const std::string models_dir_;
  const double step_s_;
  const pb::FrameRecording mode_;
  const ReplayOptions& options_;
  std::optional<LoadedScene> loaded_;
  std::map<std::string, Isometry3d> applied_;
  int64_t step_ = 0;
  pb::RecordedFrame replayed_;
};

// The first field in which `replayed` differs from `recorded`.
std::string FirstDifference(const pb::RecordedFrame& recorded, const pb::RecordedFrame& replayed) {
  if (recorded.has_sha256()) {
    return recorded.sha256() == replayed.sha256() ? "" : "frame digest";
  }
  std::string report;
  google::protobuf::util::MessageDifferencer differencer;
  differencer.ReportDifferencesToString(&report);
  if (differencer.Compare(recorded.frame(), replayed.frame())) return "";
  const size_t end = report.find('\n');
  return report.substr(0, end);
}

}  // namespace

absl::StatusOr<ReplayReport> ReplayRecording(const std::string& file,
                                             const ReplayOptions& options) {
  absl::StatusOr<RecordedSession> session = ReadSession(file);
  if (!session.ok()) return session.status();
  const pb::RecordingStart& start = session->records.front().start();
  if (start.part() != 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        file, " is part ", start.part(), " of its session: replay from the session's first file"));
  }
  ReplayReport report;
  report.files = session->files;
  ReplayedScene scene(options.uploaded_models_dir.empty() ? start.uploaded_models_dir()
                                                          : options.uploaded_models_dir,
                      start.step_s(), start.frames(), options);
  if (absl::Status s = scene.Start(start); !s.ok()) return s;
  for (size_t i = 1; i < session->records.size(); ++i) {
    const pb::Record& record = session->records[i];
    absl::Status status;
    switch (record.kind_case()) {
      case pb::Record::kEdit:
        status = scene.Edit(record.edit());
        break;
      case pb::Record::kInput:
        status = scene.Input(record.input());
        break;
      case pb::Record::kFrame: {
        absl::StatusOr<const pb::RecordedFrame*> replayed = scene.Step(record.frame());
        if (!replayed.ok()) return replayed.status();
        ++report.steps_compared;
        const std::string difference = FirstDifference(record.frame(), **replayed);
        if (difference.empty()) {
          ++report.identical;
        } else if (report.first_divergent_step == 0) {
          report.first_divergent_step = record.frame().step();
          report.first_divergent_field = difference;
        }
        break;
      }
      case pb::Record::kStart:  // the next part: it carries on from here
        if (record.start().after_step() != scene.step()) {
          return absl::InvalidArgumentError(absl::StrCat(
              "part ", record.start().part(), " starts after step ", record.start().after_step(),
              ", the part before ends at ", scene.step()));
        }
        break;
      case pb::Record::kGap:
        report.stopped_early = absl::StrCat(
            "the recorder skipped ", record.gap().steps(), " steps from step ",
            record.gap().first_step(), " (its queue was full): replayed up to step ", scene.step());
        return report;
      default:  // stream changes and the end: nothing to re-run
        break;
    }
    if (!status.ok()) return status;
  }
  return report;
}

}  // namespace hs
