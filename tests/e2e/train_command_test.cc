// `hapticctl train` and `score` against an in-process server: the bundled
// exercise driven live along its bundled path is completed as it is
// offline; the recording of that drive scores exactly as the path the
// server applied; two trainees on two tools are scored at once by one
// train while an instructor watches; a scene deleted mid-exercise ends it
// with a partial summary marked incomplete.

#include "client/training/train_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "client/device_path.h"
#include "client/exit_codes.h"
#include "client/training/score_command.h"
#include "client/watch_command.h"
#include "common/api/proto_convert.h"
#include "common/api/scene_file.h"
#include "common/recording/recorded_step.h"
#include "common/recording/session_reader.h"
#include "nlohmann/json.hpp"
#include "tests/common/scratch_dir.h"
#include "tests/server/test_server.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;

const std::string kScenes = HS_SCENES_DIR;
const std::string kExercise = kScenes + "/exercises/three_points.textproto";

// Plays `path` into `tool` in real time on its own Interact stream.
void Drive(hs::testing::TestServer& server, const std::string& scene, const std::string& tool,
           const std::vector<TimedPose>& path) {
  grpc::ClientContext context;
  auto stream = hs::testing::OpenDevice(server.sessions(), context, scene, tool);
  ASSERT_NE(stream, nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < path.size(); ++i) {
    std::this_thread::sleep_until(t0 + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                           std::chrono::duration<double>(path[i].t_s)));
    pb::InteractRequest pose;
    pose.mutable_pose()->set_sequence(i + 1);
    PoseToProto(path[i].X_WD, pose.mutable_pose()->mutable_pose());
    ASSERT_TRUE(stream->Write(pose));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let the last hold finish
  stream->WritesDone();
  pb::Frame frame;
  while (stream->Read(&frame)) {
  }
  stream->Finish();
}

// `train --json` on `exercises` against `server`, in a thread of its own
// from construction; Join() waits for it to end.
struct TrainRun {
  TrainRun(hs::testing::TestServer& server, std::vector<std::string> exercises) {
    thread = std::thread([this, address = server.address(), exercises = std::move(exercises)] {
      TrainArgs args{.exercises = exercises, .json = true};
      args.server.address = address;
      status = RunTrain(args, out, err, stop);
    });
  }
  void Join() { thread.join(); }

  std::ostringstream out, err;
  std::atomic<bool> stop{false};
  int status = -1;
  std::thread thread;
};

std::vector<nlohmann::json> Lines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

TEST(TrainCommandTest, LiveRunIsScoredAsOffline) {
  hs::testing::TestServer server;
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok());
  server.Create(*spec);
  absl::StatusOr<std::vector<TimedPose>> path =
      ReadDevicePath(kScenes + "/exercises/three_points_path.jsonl", 1000);
  ASSERT_TRUE(path.ok());
  TrainRun train(server, {kExercise});
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // attached before the motion
  Drive(server, spec->name(), "probe", *path);
  train.stop = true;
  train.Join();
  ASSERT_EQ(train.status, kExitOk) << train.err.str();
  const std::vector<nlohmann::json> lines = Lines(train.out.str());
  ASSERT_EQ(lines.size(), 1u) << train.out.str();
  const nlohmann::json& live = lines[0];
  std::ostringstream offline_out, offline_err;
  ASSERT_EQ(RunScore({.exercise = kExercise,
                      .path = kScenes + "/exercises/three_points_path.jsonl",
                      .json = true},
                     offline_out, offline_err),
            kExitOk);
  const nlohmann::json offline = nlohmann::json::parse(offline_out.str());
  std::cout << "live " << live.dump() << "\noffline " << offline.dump() << "\n";
  EXPECT_EQ(live["ended"], "done");
  EXPECT_EQ(live["completed"], offline["completed"]);
  EXPECT_EQ(live["targets_reached"], offline["targets_reached"]);
  EXPECT_EQ(live["forbidden_contacts"], offline["forbidden_contacts"]);
  // Real time moves the steps the poses land on: the same motion within 5 %.
  EXPECT_NEAR(live["path_length_m"].get<double>(), offline["path_length_m"].get<double>(),
              0.05 * offline["path_length_m"].get<double>());
  EXPECT_NEAR(live["max_force_n"].get<double>(), offline["max_force_n"].get<double>(),
              0.1 * offline["max_force_n"].get<double>());
}

// The device inputs of a recorded session as a JSON lines path: each pose
// at the time of the step before the one it was applied to, so that
// `score --path` applies it where the server did.
std::string PathOfRecording(const std::string& recording, const std::string& out) {
  absl::StatusOr<RecordedSession> session = ReadSession(recording);
  EXPECT_TRUE(session.ok()) << session.status();
  std::ofstream file(out);
  file << nlohmann::json{{"scene", session->records.front().start().spec().name()}}.dump() << "\n";
  const double step_s = session->records.front().start().step_s();
  for (const pb::Record& record : session->records) {
    if (!record.has_input()) continue;
    absl::StatusOr<Isometry3d> X_WD = ExactPoseFromProto(record.input().device_pose());
    EXPECT_TRUE(X_WD.ok());
    const Eigen::AngleAxisd r(X_WD->rotation());
    const Vector3d v = r.axis() * r.angle();
    const Vector3d p = X_WD->translation();
    file << nlohmann::json{{"t_s", static_cast<double>(record.input().step() - 1) * step_s},
                           {"pose",
                            nlohmann::json::array({p.x(), p.y(), p.z(), v.x(), v.y(), v.z()})}}
                .dump()
         << "\n";
  }
  return out;
}

// The bundled path driven through a recording server: scoring the
// recording and scoring the poses the server applied, as a path, give the
// same summary, field for field.
TEST(TrainCommandTest, RecordingScoresAsThePathItApplied) {
  const std::filesystem::path dir = ScratchDir("score_recording");
  RecordingOptions recording;
  recording.dir = (dir / "recordings").string();
  // Digests, and a queue of 10 s: a loaded machine's slow disk must not
  // make the recorder skip steps (a gap no replay crosses).
  recording.frames = haptics::v1::FRAME_RECORDING_DIGEST;
  recording.queue_steps = 10'000;
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok());
  absl::StatusOr<std::vector<TimedPose>> path =
      ReadDevicePath(kScenes + "/exercises/three_points_path.jsonl", 1000);
  ASSERT_TRUE(path.ok());
  {
    hs::testing::TestServer server({}, recording);
    server.Create(*spec);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the scene idles first
    Drive(server, spec->name(), "probe", *path);
  }  // the server's end closes the recording
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(recording.dir)) {
    files.push_back(entry.path().string());
  }
  ASSERT_EQ(files.size(), 1u);
  const std::string applied = PathOfRecording(files[0], (dir / "applied.jsonl").string());
  auto score = [](ScoreArgs args) {
    args.exercise = kExercise;
    args.json = true;
    std::ostringstream out, err;
    EXPECT_EQ(RunScore(args, out, err), kExitOk) << err.str();
    return nlohmann::json::parse(out.str());
  };
  const nlohmann::json from_recording = score({.recording = files[0]});
  const nlohmann::json from_path = score({.path = applied});
  std::cout << "recording " << from_recording.dump() << "\npath " << from_path.dump() << "\n";
  EXPECT_TRUE(from_recording["completed"]);
  EXPECT_EQ(from_recording, from_path);
}

// A scene of two tools (the demo scene and a stylus over the organ's west
// side) and an exercise each: each pressed onto its own point, both
// scored at once by one train, while an instructor's watch sees both.
TEST(TrainCommandTest, TwoTraineesAtOnce) {
  const std::filesystem::path dir = ScratchDir("two_trainees");
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok());
  spec->set_name("two trainees");
  pb::SceneObject* stylus = spec->add_objects();
  *stylus = spec->objects(2);
  stylus->set_name("stylus");
  stylus->mutable_pose()->mutable_position_m()->set_x(-0.1);
  {
    std::ofstream scene_file(dir / "scene.textproto");
    scene_file << spec->DebugString();
  }
  auto exercise = [&](const std::string& tool, double x) {
    const std::string file = (dir / (tool + ".textproto")).string();
    std::ofstream(file) << "name: \"" << tool << "\" scene_file: \"scene.textproto\" tool: \""
                        << tool << "\" targets { object: \"organ\" sphere { center_m { x: " << x
                        << " z: 0.04 } radius_m: 0.015 } min_force_n: 0.5 hold_s: 0.2 }"
                        << " forbidden { object: \"table\" } time_limit_s: 10";
    return file;
  };
  hs::testing::TestServer server;
  server.Create(*spec);
  TrainRun train(server, {exercise("probe", 0.1), exercise("stylus", -0.1)});
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto press = [](double x) {
    std::vector<TimedPose> path;
    for (int i = 0; i <= 100; ++i) {
      TimedPose p{.t_s = 0.005 * i};
      p.X_WD.translation() = Vector3d(x, 0, 0.1 - 0.013 * std::min(1.0, i / 40.0));
      path.push_back(p);
    }
    return path;
  };
  // The instructor watches both at once.
  std::ostringstream watch_out, watch_err;
  int watch_status = -1;
  std::thread instructor([&] {
    WatchArgs args{.scene = "two trainees", .parts = {"contacts"}, .json = true, .duration_s = 1.5};
    args.server.address = server.address();
    watch_status = RunWatch(args, watch_out, watch_err);
  });
  std::thread second([&] { Drive(server, "two trainees", "stylus", press(-0.1)); });
  Drive(server, "two trainees", "probe", press(0.1));
  second.join();
  instructor.join();
  ASSERT_EQ(watch_status, kExitOk) << watch_err.str();
  // Some frame shows both trainees pressing the organ.
  const std::vector<nlohmann::json> seen = Lines(watch_out.str());
  ASSERT_FALSE(seen.empty());
  std::cout << seen.back().dump() << "\n";
  EXPECT_TRUE(std::any_of(seen.begin(), seen.end(), [](const nlohmann::json& frame) {
    int touching = 0;
    for (const nlohmann::json& tool : frame["tools"]) touching += tool.contains("contacts");
    return touching == 2;
  }));
  train.stop = true;
  train.Join();
  ASSERT_EQ(train.status, kExitOk) << train.err.str();
  const std::vector<nlohmann::json> lines = Lines(train.out.str());
  ASSERT_EQ(lines.size(), 2u) << train.out.str();
  for (const nlohmann::json& line : lines) {
    SCOPED_TRACE(line.dump());
    EXPECT_EQ(line["ended"], "done");
    EXPECT_TRUE(line["completed"]);
    EXPECT_EQ(line["forbidden_contacts"], 0);
  }
  EXPECT_EQ(lines[0]["tool"], "probe");
  EXPECT_EQ(lines[1]["tool"], "stylus");
}

// The scene is deleted a moment in: train ends with the summary so far,
// not completed, naming why, and the exit status of UNAVAILABLE.
TEST(TrainCommandTest, SceneGoneMidExerciseGivesAPartialSummary) {
  hs::testing::TestServer server;
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok());
  server.Create(*spec);
  TrainRun train(server, {kExercise});
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  pb::DeleteSceneRequest request;
  request.set_scene(spec->name());
  pb::DeleteSceneResponse response;
  ASSERT_TRUE(
      server.scenes().DeleteScene(hs::testing::ContextWithin(10).get(), request, &response).ok());
  train.Join();
  EXPECT_EQ(train.status, kExitUnavailable) << train.err.str();
  const std::vector<nlohmann::json> lines = Lines(train.out.str());
  ASSERT_EQ(lines.size(), 1u) << train.out.str();
  EXPECT_FALSE(lines[0]["completed"]);
  EXPECT_NE(lines[0]["ended"].get<std::string>().find("UNAVAILABLE"), std::string::npos)
      << lines[0].dump();
}

}  // namespace
}  // namespace hs::cli
