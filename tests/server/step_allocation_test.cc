// The server's per-step path allocates nothing in steady state: the scene
// runner steps the demo scene with every effect, copies each frame into a
// pooled snapshot and fans it out to two attached streams, which queue it
// in their outboxes and build their messages on their arenas as the
// session service does. A binary of its own: it links the counting global
// operator new. What gRPC allocates to send the bytes is gRPC's.

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "client/tool_path.h"
#include "common/api/scene_file.h"
#include "server/frame_message.h"
#include "server/frame_outbox.h"
#include "server/scene_runner.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/test_data_dir.h"

namespace hs {
namespace {

// A stream as the session service runs one, its gRPC write replaced by
// serializing into a reused string.
class SerializingSink : public FrameSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    outbox_.Push(std::move(snapshot));
    FrameOutbox::Next next = outbox_.TakeNext();
    if (next.kind != FrameOutbox::Next::kWrite) return;
    haptics::v1::Frame& message = arena_.Start();
    FillFrameMessage(*next.snapshot, FrameParts{}, this, next.dropped, 0, models_sent_, message);
    message.SerializeToString(&bytes_);
    outbox_.WriteDone();
    contacts_ += message.tools_size() > 0 ? message.tools(0).contacts_size() : 0;
    last_step_.store(next.snapshot->step, std::memory_order_release);
  }
  void Close(const absl::Status&) override {}

  int64_t last_step() const { return last_step_.load(std::memory_order_acquire); }
  // Contacts written over the run: the test means something only if the
  // tool touched.
  int64_t contacts() const { return contacts_; }

 private:
  FrameOutbox outbox_{8};
  FrameMessageArena arena_;
  ModelsSent models_sent_;
  std::string bytes_;
  std::atomic<int64_t> last_step_{0};
  int64_t contacts_ = 0;  // scene-frames thread only
};

TEST(StepAllocationTest, ThousandDemoStepsWithTwoStreamsAllocateNothing) {
  const std::string scenes = hs::ScenesDir();
  absl::StatusOr<haptics::v1::SceneSpec> spec = ReadSceneFile(scenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(spec.ok()) << spec.status();
  absl::StatusOr<LoadedScene> loaded = LoadSceneFile(scenes + "/probe_on_torus.textproto");
  ASSERT_TRUE(loaded.ok()) << loaded.status();
  const absl::StatusOr<std::vector<Isometry3d>> path =
      cli::ReadToolPath(scenes + "/press_and_slide.csv");
  ASSERT_TRUE(path.ok()) << path.status();
  Metrics metrics;
  SceneRunner runner(*spec, *std::move(loaded), metrics);
  SerializingSink device, viewer;
  // Every effect a stream gets by default (the local model is left out:
  // its planes' copies into the step's snapshot are not yet checked).
  ASSERT_TRUE(runner.AttachDevice(&device, {"probe", EffectSet::Default()}).ok());
  ASSERT_TRUE(runner.AttachViewer(&viewer, EffectSet::Default()).ok());

  // One step per pose, the path walked there and back; the device's pose
  // clocks the step, and the next pose waits for its frame.
  uint64_t sequence = 0;
  auto drive = [&](int steps) {
    for (int i = 0; i < steps; ++i) {
      const size_t lap = 2 * path->size(), k = sequence % lap;
      const Isometry3d& X = (*path)[k < path->size() ? k : lap - 1 - k];
      const int64_t before = device.last_step();
      runner.SetDevicePose(&device, X, AppliedPose{++sequence, 0});
      while (device.last_step() <= before || viewer.last_step() < device.last_step()) {
        std::this_thread::yield();
      }
    }
  };
  // Warm-up: the buffers a step reuses grow to the most its contacts need.
  // The proxy's state carries over from lap to lap, so a later lap can
  // meet a contact larger than any before and a buffer grows again
  // (geometrically: ever more rarely). Steady state: a stretch of 1,000 steps that allocates
  // nothing, within ten such stretches after four laps.
  drive(8 * static_cast<int>(path->size()));
  std::vector<long> allocations;
  while (allocations.size() < 10 && (allocations.empty() || allocations.back() != 0)) {
    const long before = AllocationCount();
    drive(1000);
    allocations.push_back(AllocationCount() - before);
  }
  runner.Detach(&device);
  runner.Detach(&viewer);
  runner.Stop(absl::CancelledError("done"));
  EXPECT_EQ(allocations.back(), 0) << ::testing::PrintToString(allocations);
  EXPECT_GT(device.contacts(), 100);
}

}  // namespace
}  // namespace hs
