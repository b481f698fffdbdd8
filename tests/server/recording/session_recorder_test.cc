// A scene runner records its session; replaying the recording re-runs it
// bit for bit (the demo scene: a probe pressed into and slid along a torus,
// every effect, an edit halfway), and a changed frame is found at its step
// and field; a free body's poses are kept in the frames.

#include "server/recording/session_recorder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "client/tool_path.h"
#include "common/api/scene_file.h"
#include "common/recording/record_file.h"
#include "common/recording/recording_summary.h"
#include "common/recording/replay.h"
#include "google/protobuf/text_format.h"
#include "server/scene_runner.h"
#include "tests/common/scratch_dir.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

const std::string kScenes = hs::ScenesDir();

// A device stream that only notes the last step it was offered.
class StepSink : public FrameSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    last_step_.store(snapshot->step, std::memory_order_release);
  }
  void Close(const absl::Status&) override {}
  int64_t last_step() const { return last_step_.load(std::memory_order_acquire); }

 private:
  std::atomic<int64_t> last_step_{0};
};

// Runs `spec` (its models read from the scenes folder) with a recorder, a
// device on its tool `tool` taking every effect, and `drive` driving it.
// Returns the session's first file.
std::string Record(const pb::SceneSpec& spec, const std::string& tool, RecordingOptions options,
                   const std::function<void(SceneRunner&, StepSink&)>& drive) {
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, kScenes);
  EXPECT_TRUE(loaded.ok());
  Metrics metrics;
  absl::StatusOr<std::unique_ptr<SessionRecorder>> recorder = SessionRecorder::Start(
      options, {spec.name(), spec, 0, loaded->scene->options().step_s, ""}, metrics);
  EXPECT_TRUE(recorder.ok()) << recorder.status();
  const std::string file = (*recorder)->path();
  SceneRunner runner(spec, *std::move(loaded), metrics, {}, *std::move(recorder));
  StepSink device;
  EXPECT_TRUE(runner.AttachDevice(&device, {tool, EffectSet::All()}).ok());
  drive(runner, device);
  runner.Detach(&device);
  runner.Stop(absl::CancelledError("done"));
  return file;
}

// Runs the demo scene with a recorder, walks the device path once (each
// pose waits for its frame, and asks `model` of the local model, a fresh
// one every `stale_every` poses when > 0), and with `edit` moves the organ
// 1 mm up halfway. Returns the session's first file.
std::string RecordDemo(RecordingOptions options, bool edit, LocalModelRequest model = {},
                       size_t stale_every = 0) {
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(kScenes + "/probe_on_torus.textproto");
  EXPECT_TRUE(spec.ok());
  const absl::StatusOr<std::vector<Isometry3d>> path =
      cli::ReadToolPath(kScenes + "/press_and_slide.csv");
  EXPECT_TRUE(path.ok());
  return Record(*spec, "probe", std::move(options), [&](SceneRunner& runner, StepSink& device) {
    uint64_t sequence = 0;
    for (size_t i = 0; i < path->size(); ++i) {
      if (edit && i == path->size() / 2) {
        pb::SceneSpec moved = *spec;
        moved.mutable_objects(1)->mutable_pose()->mutable_position_m()->set_z(0.041);
        absl::StatusOr<LoadedScene> rebuilt = BuildScene(moved, kScenes);
        EXPECT_TRUE(rebuilt.ok());
        EXPECT_TRUE(runner.Replace(moved, *std::move(rebuilt)).ok());
      }
      const int64_t before = device.last_step();
      model.stale = stale_every > 0 && i % stale_every == 0;
      runner.SetDevicePose(&device, (*path)[i], AppliedPose{++sequence, 0}, model);
      while (device.last_step() <= before + 1) std::this_thread::yield();
    }
  });
}

RecordingOptions Options(const std::string& dir) {
  RecordingOptions options;
  options.dir = ScratchDir(dir).string();
  return options;
}

// Frames in full: every step re-runs to the same frame, contacts and all,
// across the edit.
TEST(SessionRecorderTest, FullFramesReplayBitForBit) {
  const std::string file = RecordDemo(Options("full"), /*edit=*/true);
  absl::StatusOr<RecordingSummary> summary = SummarizeRecording(file);
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_TRUE(summary->ended);
  EXPECT_EQ(summary->edits, 1);
  EXPECT_GT(summary->inputs, 50);
  EXPECT_EQ(summary->device_tools, std::set<std::string>{"probe"});
  // The sample must touch: frames with contacts and forces.
  absl::StatusOr<RecordFileContents> contents = ReadRecordFile(file);
  ASSERT_TRUE(contents.ok());
  int touching = 0;
  for (const pb::Record& r : contents->records) {
    touching += r.has_frame() && r.frame().frame().tools_size() > 0 &&
                r.frame().frame().tools(0).contacts_size() > 0;
  }
  EXPECT_GT(touching, 20);

  absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->all_identical())
      << report->first_divergent_step << " " << report->first_divergent_field;
  EXPECT_EQ(report->steps_compared, summary->steps);
}

// A remote device's requests of its local model (its radius, the surface
// alone, a fresh model now and then) are recorded with its poses, and the
// replay asks the same: bit for bit.
TEST(SessionRecorderTest, LocalModelRequestsAreRecordedWithThePoses) {
  const std::string file =
      RecordDemo(Options("model"), /*edit=*/false,
                 {.validity_radius_m = 0.02, .surface_only = true}, /*stale_every=*/10);
  absl::StatusOr<RecordFileContents> contents = ReadRecordFile(file);
  ASSERT_TRUE(contents.ok());
  int inputs = 0, stale = 0;
  for (const pb::Record& r : contents->records) {
    if (!r.has_input()) continue;
    ++inputs;
    EXPECT_EQ(r.input().validity_radius_m(), 0.02);
    EXPECT_TRUE(r.input().surface_only());
    stale += r.input().model_stale();
  }
  EXPECT_GT(inputs, 50);
  EXPECT_GT(stale, 0);
  EXPECT_LT(stale, inputs);
  absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->all_identical())
      << report->first_divergent_step << " " << report->first_divergent_field;
}

// Digests only: as exact, in a fraction of the bytes.
TEST(SessionRecorderTest, DigestFramesReplayBitForBit) {
  RecordingOptions options = Options("digest");
  options.frames = pb::FRAME_RECORDING_DIGEST;
  const std::string file = RecordDemo(options, /*edit=*/false);
  absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->all_identical());
  EXPECT_GT(report->steps_compared, 50);
}

// A frame changed in the file (a force off by 1e-12 N) is the first
// divergence, at its step and field; the others stay identical.
TEST(SessionRecorderTest, ChangedFrameIsTheFirstDivergence) {
  const std::string file = RecordDemo(Options("changed"), /*edit=*/false);
  absl::StatusOr<RecordFileContents> contents = ReadRecordFile(file);
  ASSERT_TRUE(contents.ok());
  int64_t changed_step = 0;
  const std::string changed = (ScratchDir("changed_copy") / "changed.hsrec").string();
  absl::StatusOr<RecordFileWriter> writer = RecordFileWriter::Create(changed);
  ASSERT_TRUE(writer.ok());
  for (pb::Record& r : contents->records) {
    if (changed_step == 0 && r.has_frame() && r.frame().frame().tools_size() > 0 &&
        r.frame().frame().tools(0).force_w_n().z() != 0) {
      changed_step = r.frame().step();
      pb::Vector3* force =
          r.mutable_frame()->mutable_frame()->mutable_tools(0)->mutable_force_w_n();
      force->set_z(force->z() + 1e-12);
    }
    ASSERT_TRUE(writer->Append(r).ok());
  }
  ASSERT_GT(changed_step, 0);
  absl::StatusOr<ReplayReport> report = ReplayRecording(changed, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_FALSE(report->all_identical());
  EXPECT_EQ(report->first_divergent_step, changed_step);
  EXPECT_NE(report->first_divergent_field.find("force_W_n.z"), std::string::npos)
      << report->first_divergent_field;
  EXPECT_EQ(report->identical, report->steps_compared - 1);
}

// A recording keeps the free bodies of its frames: a cube dropped 2 cm
// onto the floor is in every frame that moved it, read back from the file
// falling from its start (centre at 3 cm) to rest on the floor (centre at
// half its 2 cm side, within 0.1 mm), and the replay re-runs it bit for
// bit, bodies included.
TEST(SessionRecorderTest, FreeBodiesAreRecorded) {
  pb::SceneSpec spec;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      R"pb(
        name: "cube drop"
        objects {
          name: "floor"
          kind: OBJECT_KIND_FIXED
          model { procedural { box { size_m { x: 1 y: 1 z: 0.1 } } } }
          pose {
            position_m { z: -0.05 }
            orientation { w: 1 }
          }
        }
        objects {
          name: "cube"
          kind: OBJECT_KIND_FREE
          model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } }
          pose {
            position_m { z: 0.03 }
            orientation { w: 1 }
          }
        }
        objects {
          name: "probe"
          kind: OBJECT_KIND_TOOL
          model { procedural { box { size_m { x: 0.02 y: 0.02 z: 0.02 } } } }
          pose {
            position_m { x: 0.3 z: 0.1 }
            orientation { w: 1 }
          }
        }
      )pb",
      &spec));
  // 0.3 s: the 2 cm fall takes 64 ms, then the cube settles.
  const std::string file =
      Record(spec, "probe", Options("bodies"), [](SceneRunner&, StepSink& device) {
        while (device.last_step() < 300) std::this_thread::yield();
      });
  absl::StatusOr<RecordFileContents> contents = ReadRecordFile(file);
  ASSERT_TRUE(contents.ok()) << contents.status();
  std::vector<double> heights;
  for (const pb::Record& r : contents->records) {
    if (!r.has_frame()) continue;
    const pb::Frame& frame = r.frame().frame();
    const bool moved = std::find(frame.stages_run().begin(), frame.stages_run().end(),
                                 pb::EFFECT_FREE_BODY_MOTION) != frame.stages_run().end();
    ASSERT_EQ(frame.bodies_size(), moved ? 1 : 0) << "step " << frame.step();
    if (!moved) continue;
    EXPECT_EQ(frame.bodies(0).name(), "cube");
    EXPECT_FALSE(frame.bodies(0).held());
    heights.push_back(frame.bodies(0).pose().position_m().z());
  }
  ASSERT_GT(heights.size(), 200u);
  EXPECT_LE(heights.front(), 0.03);
  EXPECT_GT(heights.front(), 0.029);
  EXPECT_NEAR(heights.back(), 0.01, 1e-4);

  absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->all_identical())
      << report->first_divergent_step << " " << report->first_divergent_field;
}

// Past the size cap a session goes on in its next part: replaying the
// first file runs through all of them; cut short (a crash tearing the
// last record), what remains still replays bit for bit.
TEST(SessionRecorderTest, RolledOverAndTornSessionsReplay) {
  RecordingOptions options = Options("parts");
  options.max_file_bytes = 16 << 10;
  const std::string file = RecordDemo(options, /*edit=*/true);
  absl::StatusOr<ReplayReport> report = ReplayRecording(file, {});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->all_identical());
  ASSERT_GT(report->files.size(), 2u);
  const std::string last = report->files.back().path;
  const auto size = std::filesystem::file_size(last);
  std::filesystem::resize_file(last, size - 5);
  absl::StatusOr<ReplayReport> torn = ReplayRecording(file, {});
  ASSERT_TRUE(torn.ok()) << torn.status();
  EXPECT_TRUE(torn->all_identical());
  EXPECT_FALSE(torn->files.back().torn_reason.empty());
  EXPECT_LE(torn->steps_compared, report->steps_compared);
  // A later part alone is no session to replay.
  EXPECT_EQ(ReplayRecording(report->files[1].path, {}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace hs
