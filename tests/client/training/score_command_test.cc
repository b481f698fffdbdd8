// `hapticctl score --path` on the bundled exercise: the bundled path
// completes it; the same path pressed 1 cm into the organ (4 N against the
// 3 N limit) and the same path after a touch of the forbidden table score
// lower. Bad exercises name the field at fault.

#include "client/training/score_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "client/device_path.h"
#include "client/exit_codes.h"
#include "common/api/exercise_file.h"
#include "common/api/scene_file.h"
#include "common/recording/record_file.h"
#include "common/recording/recorded_step.h"
#include "nlohmann/json.hpp"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs::cli {
namespace {

const std::string kExercise = hs::ScenesDir() + "/exercises/three_points.textproto";
const std::string kPath = hs::ScenesDir() + "/exercises/three_points_path.jsonl";

nlohmann::json Score(const std::string& path, const std::string& recording = "") {
  std::ostringstream out, err;
  EXPECT_EQ(RunScore({.exercise = kExercise, .path = path, .recording = recording, .json = true},
                     out, err),
            0)
      << err.str();
  return nlohmann::json::parse(out.str());
}

// Writes `poses` as JSON lines (the poses' rotations are the identity).
std::string WritePath(const std::string& name, const std::vector<TimedPose>& poses) {
  const std::string file = (ScratchDir("paths") / name).string();
  std::ofstream out(file);
  for (const TimedPose& p : poses) {
    const Vector3d& x = p.X_WD.translation();
    out << nlohmann::json{{"t_s", p.t_s}, {"pose", {x.x(), x.y(), x.z(), 0, 0, 0}}}.dump() << "\n";
  }
  return file;
}

TimedPose At(double t, const Vector3d& p) {
  TimedPose pose{.t_s = t};
  pose.X_WD.translation() = p;
  return pose;
}

TEST(ScoreCommandTest, GentleBeatsPressedAndForbidden) {
  absl::StatusOr<std::vector<TimedPose>> gentle = ReadDevicePath(kPath, 1000);
  ASSERT_TRUE(gentle.ok()) << gentle.status();
  // Pressed: every point held 3 mm in (z = 0.087) is held 1 cm in.
  std::vector<TimedPose> pressed = *gentle;
  for (TimedPose& p : pressed) {
    if (p.X_WD.translation().z() < 0.0875) p.X_WD.translation().z() = 0.08;
  }
  // Forbidden: first over to the table beside the organ and 2 mm into it.
  const Vector3d home = gentle->front().X_WD.translation();
  std::vector<TimedPose> table = {At(0, home), At(0.3, Vector3d(0.3, 0, 0.1)),
                                  At(0.6, Vector3d(0.3, 0, 0.008)), At(0.9, Vector3d(0.3, 0, 0.1)),
                                  At(1.2, home)};
  for (const TimedPose& p : *gentle) table.push_back(At(1.5 + p.t_s, p.X_WD.translation()));

  const nlohmann::json g = Score(kPath);
  const nlohmann::json p = Score(WritePath("pressed.jsonl", pressed));
  const nlohmann::json t = Score(WritePath("table.jsonl", table));
  std::cout << "gentle " << g.dump() << "\npressed " << p.dump() << "\ntable " << t.dump() << "\n";
  EXPECT_TRUE(g["completed"]);
  EXPECT_EQ(g["targets_reached"], 3);
  EXPECT_EQ(g["forbidden_contacts"], 0);
  EXPECT_EQ(g["excess_impulse_ns"], 0);
  EXPECT_LE(g["max_force_n"].get<double>(), 3);
  EXPECT_GT(p["excess_impulse_ns"].get<double>(), 0);
  EXPECT_GT(p["force_limit_exceeded_s"].get<double>(), 0);
  EXPECT_GE(t["forbidden_contacts"].get<int>(), 1);
  EXPECT_GT(g["score"].get<double>(), p["score"].get<double>());
  EXPECT_GT(g["score"].get<double>(), t["score"].get<double>());
  for (const char* key : {"score", "completed", "duration_s", "targets_reached", "path_length_m",
                          "economy", "max_force_n", "force_limit_exceeded_s", "excess_impulse_ns",
                          "forbidden_contacts", "jerk_rms"}) {
    EXPECT_TRUE(g.contains(key)) << key;
  }
}

// A recorded session of the same motion: the server's inputs are the
// path's poses at the steps the offline run applies them (step k + 1 takes
// the newest pose due by k * step_s), the first one seating the device,
// each stamped with its time on the path as the device's clock, as a
// server records a device's stream. Scored through the recording (re-run
// by replay), it gives the offline run's summary exactly. A recording of
// another scene is refused by name.
std::string RecordPath(const std::string& name, const std::vector<TimedPose>& path,
                       const std::string& scene_name, int64_t gap_at_step = 0) {
  namespace pb = haptics::v1;
  const std::string file = (ScratchDir("recordings") / name).string();
  absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(file);
  EXPECT_TRUE(writer.ok()) << writer.status();
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(hs::ScenesDir() + "/probe_on_torus.textproto");
  EXPECT_TRUE(spec.ok());
  spec->set_name(scene_name);
  pb::Record record;
  pb::RecordingStart* start = record.mutable_start();
  *start->mutable_spec() = *spec;
  start->set_step_s(0.001);
  start->set_frames(pb::FRAME_RECORDING_DIGEST);
  EXPECT_TRUE(writer->Append(record).ok());
  size_t next = 0;
  const int64_t steps = static_cast<int64_t>((path.back().t_s + 0.5) / 0.001) + 1;
  for (int64_t k = 0; k < steps; ++k) {
    bool moved = false;
    while (next < path.size() && path[next].t_s <= static_cast<double>(k) * 0.001 + 1e-12) {
      ++next;
      moved = true;
    }
    if (moved) {
      record.Clear();
      pb::DeviceInput* input = record.mutable_input();
      input->set_step(k + 1);
      input->set_tool("probe");
      input->set_seat(k == 0);
      // The device's clock reads the path's times.
      input->set_device_time_ns(std::llround(path[next - 1].t_s * 1e9));
      ExactPoseToProto(path[next - 1].X_WD, input->mutable_device_pose());
      EXPECT_TRUE(writer->Append(record).ok());
    }
    record.Clear();
    if (k + 1 == gap_at_step) {  // the recorder skipped this step
      record.mutable_gap()->set_first_step(k + 1);
      record.mutable_gap()->set_steps(1);
      EXPECT_TRUE(writer->Append(record).ok());
      continue;
    }
    record.mutable_frame()->set_step(k + 1);
    record.mutable_frame()->set_sha256("not compared");
    EXPECT_TRUE(writer->Append(record).ok());
  }
  return file;
}

TEST(ScoreCommandTest, ARecordingOfThePathScoresTheSame) {
  absl::StatusOr<std::vector<TimedPose>> path = ReadDevicePath(kPath, 1000);
  ASSERT_TRUE(path.ok());
  const nlohmann::json offline = Score(kPath);
  const nlohmann::json recorded = Score("", RecordPath("same.hsrec", *path, "probe on torus"));
  EXPECT_EQ(offline.dump(), recorded.dump());
  std::ostringstream out, err;
  const std::string other = RecordPath("other.hsrec", *path, "another scene");
  EXPECT_NE(RunScore({.exercise = kExercise, .recording = other}, out, err), 0);
  EXPECT_NE(err.str().find("records scene 'another scene'"), std::string::npos) << err.str();
}

// A recording with a gap (steps its recorder skipped) is scored up to the
// gap, said on stderr, and not completed.
TEST(ScoreCommandTest, ARecordingWithAGapIsScoredUpToIt) {
  absl::StatusOr<std::vector<TimedPose>> path = ReadDevicePath(kPath, 1000);
  ASSERT_TRUE(path.ok());
  const std::string file = RecordPath("gap.hsrec", *path, "probe on torus", 1000);
  std::ostringstream out, err;
  ASSERT_EQ(RunScore({.exercise = kExercise, .recording = file, .json = true}, out, err), kExitOk)
      << err.str();
  EXPECT_NE(err.str().find("scored up to there"), std::string::npos) << err.str();
  const nlohmann::json summary = nlohmann::json::parse(out.str());
  EXPECT_FALSE(summary["completed"]);
  EXPECT_LT(summary["duration_s"].get<double>(), 1.0);
}

// A path whose header names another scene is refused, naming both.
TEST(ScoreCommandTest, APathOfAnotherSceneIsRefused) {
  const std::string file = (ScratchDir("other_scene_path") / "other.jsonl").string();
  std::ofstream(file) << R"({"scene": "linked rings"})"
                      << "\n"
                      << R"({"t_s": 0, "pose": [0.1, 0, 0.1, 0, 0, 0]})"
                      << "\n";
  std::ostringstream out, err;
  EXPECT_EQ(RunScore({.exercise = kExercise, .path = file}, out, err), kExitFailure);
  EXPECT_NE(
      err.str().find("a path in scene 'linked rings', the exercise's scene is 'probe on torus'"),
      std::string::npos)
      << err.str();
}

// --report writes report.json (the summary and the attempts' scores),
// the plots, and report.html holding them inline with nothing to fetch;
// --compare adds the earlier attempts; a compared folder without a report
// is refused.
TEST(ScoreCommandTest, ReportIsSelfContained) {
  const std::filesystem::path dir = ScratchDir("reports");
  auto score = [&](const std::string& name, std::vector<std::string> compare) {
    std::ostringstream out, err;
    const int status = RunScore({.exercise = kExercise,
                                 .path = kPath,
                                 .report_dir = (dir / name).string(),
                                 .compare = std::move(compare)},
                                out, err);
    return std::make_pair(status, err.str());
  };
  ASSERT_EQ(score("first", {}).first, 0);
  const auto [status, err] = score("second", {(dir / "first").string()});
  ASSERT_EQ(status, 0) << err;
  std::ifstream json_file(dir / "second" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json_file);
  EXPECT_EQ(report["attempt_scores"].size(), 2u);
  EXPECT_TRUE(report["completed"]);
  for (const char* png : {"force.png", "path.png", "attempts.png"}) {
    EXPECT_TRUE(std::filesystem::file_size(dir / "second" / png) > 1000) << png;
  }
  std::ifstream html_file(dir / "second" / "report.html");
  const std::string html((std::istreambuf_iterator<char>(html_file)), {});
  size_t images = 0;
  for (size_t at = html.find("data:image/png;base64,"); at != std::string::npos;
       at = html.find("data:image/png;base64,", at + 1)) {
    ++images;
  }
  EXPECT_EQ(images, 3u);
  EXPECT_EQ(html.find("http"), std::string::npos) << "the report must need no network";
  EXPECT_NE(score("third", {(dir / "nothing_here").string()}).first, 0);
}

// Each bad exercise is refused with the field named; a path of poses that
// are not finite is refused too.
TEST(ScoreCommandTest, BadExercisesNameTheField) {
  const std::filesystem::path dir = ScratchDir("exercises");
  std::filesystem::copy(hs::ScenesDir() + "/probe_on_torus.textproto",
                        dir / "probe_on_torus.textproto");
  const std::string good = R"(scene_file: "probe_on_torus.textproto" tool: "probe"
    targets { object: "organ" sphere { center_m { x: 0.1 z: 0.04 } radius_m: 0.01 } }
    force_limits { object: "organ" limit_n: 3 } time_limit_s: 10 )";
  auto load = [&](const std::string& text) {
    const std::string file = (dir / "e.textproto").string();
    std::ofstream(file) << text;
    return LoadExerciseFile(file).status();
  };
  ASSERT_TRUE(load(good).ok()) << load(good);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe" time_limit_s: 10)", "targets"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "organ"
          targets { object: "organ" sphere { radius_m: 0.01 } } time_limit_s: 10)",
       "tool"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "liver" sphere { radius_m: 0.01 } } time_limit_s: 10)",
       "targets[0].object"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "organ" sphere { radius_m: -0.01 } } time_limit_s: 10)",
       "targets[0].sphere.radius_m"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "organ" sphere { radius_m: 0.01 } min_force_n: -1 } time_limit_s: 10)",
       "targets[0].min_force_n"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "organ" sphere { radius_m: 0.01 } }
          force_limits { object: "organ" limit_n: -3 } time_limit_s: 10)",
       "force_limits[0].limit_n"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "organ" sphere { radius_m: 0.01 } } forbidden { object: "floor" }
          time_limit_s: 10)",
       "forbidden[0].object"},
      {R"(scene_file: "probe_on_torus.textproto" tool: "probe"
          targets { object: "organ" sphere { radius_m: 0.01 } })",
       "time_limit_s"},
      {R"(scene_file: "missing.textproto" tool: "probe")", "missing.textproto"},
      {R"(this is not an exercise)", "ExerciseSpec"},
  };
  for (const auto& [text, field] : cases) {
    const absl::Status status = load(text);
    EXPECT_FALSE(status.ok()) << text;
    EXPECT_NE(status.message().find(field), std::string::npos)
        << status << " should name " << field;
  }
}

}  // namespace
}  // namespace hs::cli
