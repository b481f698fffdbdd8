#include "server/stream_registry.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

namespace hs {
namespace {

// A stream that records what it was told.
struct RecordingSink : FrameSink {
  void Offer(std::shared_ptr<const StepSnapshot>) override { ++offers; }
  void Close(const absl::Status& status) override { closed_with = status; }
  int offers = 0;
  std::optional<absl::Status> closed_with;
};

bool AnyTool(const std::string& tool) { return tool != "missing"; }

Isometry3d At(double x) {
  Isometry3d X = Isometry3d::Identity();
  X.translation().x() = x;
  return X;
}

// A tool is held by one device at a time; a tool the scene lacks is
// NOT_FOUND; viewers attach freely; the counts say who is there.
TEST(StreamRegistryTest, ToolsAreHeldByOneDevice) {
  StreamRegistry streams([](bool) {});
  RecordingSink a, b, viewer;
  EXPECT_EQ(streams.AttachDevice(&a, {"missing", EffectSet::All()}, AnyTool).code(),
            absl::StatusCode::kNotFound);
  EXPECT_TRUE(streams.AttachDevice(&a, {"probe", EffectSet::All()}, AnyTool).ok());
  EXPECT_EQ(streams.AttachDevice(&b, {"probe", EffectSet::All()}, AnyTool).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  StreamRegistry::Counts counts = streams.counts();
  EXPECT_EQ(counts.devices, 1);
  EXPECT_EQ(counts.viewers, 1);
  EXPECT_EQ(counts.claimed_tools, std::vector<std::string>{"probe"});
  streams.Detach(&a);
  EXPECT_TRUE(streams.AttachDevice(&b, {"probe", EffectSet::All()}, AnyTool).ok());
}

// Taking over a held tool ends its device with the given status, drops
// that device's pose not taken yet, and seats the new device on its first
// pose; the displaced device's later Detach finds nothing to free. A free
// tool is simply taken.
TEST(StreamRegistryTest, TakeOverEndsTheHolder) {
  StreamRegistry streams([](bool) {});
  RecordingSink trainee, instructor, other;
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet::All()}, AnyTool).ok());
  streams.SetPose(&trainee, At(1), {1, 0});
  const absl::Status taken = absl::AbortedError("taken over");
  bool displaced = false;
  ASSERT_TRUE(
      streams.AttachDevice(&instructor, {"probe", EffectSet::All()}, AnyTool, &taken, &displaced)
          .ok());
  EXPECT_TRUE(displaced);
  ASSERT_TRUE(trainee.closed_with.has_value());
  EXPECT_EQ(*trainee.closed_with, taken);
  EXPECT_FALSE(instructor.closed_with.has_value());
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.count, 0u);  // the trainee's pose went with it
  streams.SetPose(&instructor, At(2), {1, 0});
  streams.TakeFreshPoses(fresh);
  ASSERT_EQ(fresh.count, 1u);
  EXPECT_TRUE(fresh.taken().front().second.seat);
  EXPECT_EQ(streams.Detach(&trainee), std::nullopt);
  EXPECT_EQ(streams.counts().claimed_tools, std::vector<std::string>{"probe"});
  displaced = false;
  ASSERT_TRUE(
      streams.AttachDevice(&other, {"stylus", EffectSet::All()}, AnyTool, &taken, &displaced).ok());
  EXPECT_FALSE(displaced);
  EXPECT_EQ(streams.AttachDevice(&other, {"missing", EffectSet::All()}, AnyTool, &taken).code(),
            absl::StatusCode::kNotFound);
}

// Who holds each tool now, as a step takes it with the poses.
std::shared_ptr<const ToolHolders> Holders(StreamRegistry& streams) {
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  return fresh.holders;
}

// Frames name each held tool's holder: the map follows attaches, take-overs
// and detaches, and a map taken before a change stays as it was.
TEST(StreamRegistryTest, HoldersFollowTheDevices) {
  StreamRegistry streams([](bool) {});
  RecordingSink trainee, instructor, viewer;
  EXPECT_TRUE(Holders(streams)->empty());
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet(), "alice"}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet()).ok());
  const std::shared_ptr<const ToolHolders> before = Holders(streams);
  EXPECT_EQ(*before, (ToolHolders{{"probe", "alice"}}));
  const absl::Status taken = absl::AbortedError("taken over");
  ASSERT_TRUE(
      streams.AttachDevice(&instructor, {"probe", EffectSet(), "dr.lee"}, AnyTool, &taken).ok());
  EXPECT_EQ(*Holders(streams), (ToolHolders{{"probe", "dr.lee"}}));
  EXPECT_EQ(*before, (ToolHolders{{"probe", "alice"}}));
  streams.Detach(&instructor);
  EXPECT_TRUE(Holders(streams)->empty());
}

// A device not heard from since the cut-off is ended with the status given
// and its tool released (listed, free for another device, its pose not
// taken yet dropped); a device heard from since, and viewers, stay.
TEST(StreamRegistryTest, SilentDevicesAreEnded) {
  bool fresh_told = false;
  StreamRegistry streams([&](bool fresh) { fresh_told = fresh; });
  RecordingSink silent, talking, viewer, next;
  ASSERT_TRUE(streams.AttachDevice(&silent, {"probe", EffectSet(), "a"}, AnyTool).ok());
  streams.SetPose(&silent, At(1), {1, 0});
  const auto cut_off = std::chrono::steady_clock::now() + std::chrono::nanoseconds(1);
  std::this_thread::sleep_until(cut_off + std::chrono::milliseconds(1));
  ASSERT_TRUE(streams.AttachDevice(&talking, {"stylus", EffectSet(), "b"}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet()).ok());
  std::vector<std::string> released;
  const absl::Status status = absl::DeadlineExceededError("silent");
  streams.EndSilentDevices(cut_off, status, released);
  EXPECT_EQ(released, std::vector<std::string>{"probe"});
  ASSERT_TRUE(silent.closed_with.has_value());
  EXPECT_EQ(*silent.closed_with, status);
  EXPECT_FALSE(talking.closed_with.has_value());
  EXPECT_FALSE(viewer.closed_with.has_value());
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.count, 0u);  // the silent device's pose went with it
  EXPECT_EQ(*fresh.holders, (ToolHolders{{"stylus", "b"}}));
  // The stylus's pose now makes every device fresh.
  streams.SetPose(&talking, At(2), {1, 0});
  EXPECT_TRUE(fresh_told);
  EXPECT_TRUE(streams.AttachDevice(&next, {"probe", EffectSet(), "c"}, AnyTool).ok());
  released.clear();
  streams.EndSilentDevices(cut_off, status, released);
  EXPECT_TRUE(released.empty());
}

// A device's first pose seats it, also when a later pose replaces it before
// a step takes it; its later poses do not; the next device to take the tool
// is seated again.
TEST(StreamRegistryTest, ADevicesFirstPoseSeatsIt) {
  StreamRegistry streams([](bool) {});
  FreshPoses fresh;
  RecordingSink first, second;
  ASSERT_TRUE(streams.AttachDevice(&first, {"probe", EffectSet::All()}, AnyTool).ok());
  auto taken = [&] {
    streams.TakeFreshPoses(fresh);
    EXPECT_EQ(fresh.count, 1u);
    return fresh.taken().front().second;
  };
  streams.SetPose(&first, At(1), {1, 0});
  streams.SetPose(&first, At(2), {2, 0});
  const PendingPose seated = taken();
  EXPECT_TRUE(seated.seat);
  EXPECT_EQ(seated.X_WD.translation().x(), 2);
  streams.SetPose(&first, At(3), {3, 0});
  EXPECT_FALSE(taken().seat);
  streams.Detach(&first);
  ASSERT_TRUE(streams.AttachDevice(&second, {"probe", EffectSet::All()}, AnyTool).ok());
  streams.SetPose(&second, At(4), {1, 0});
  EXPECT_TRUE(taken().seat);
}

// The scene computes the union of what the streams need.
TEST(StreamRegistryTest, NeedsAreTheUnion) {
  StreamRegistry streams([](bool) {});
  FreshPoses fresh;
  EXPECT_EQ(streams.TakeFreshPoses(fresh), EffectSet());
  RecordingSink device, viewer;
  ASSERT_TRUE(streams.AttachDevice(&device, {"probe", EffectSet{Effect::kForce}}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet{Effect::kContactSet}).ok());
  EXPECT_EQ(streams.TakeFreshPoses(fresh), (EffectSet{Effect::kForce, Effect::kContactSet}));
}

// "Every device has a fresh pose" turns true with the last device's pose
// (or when the only silent device leaves), false when the poses are taken;
// each pose is taken once, the latest of a device winning; viewers' poses
// are ignored.
TEST(StreamRegistryTest, DevicesFreshOnceEveryDeviceSent) {
  std::vector<bool> told;
  StreamRegistry streams([&](bool fresh) { told.push_back(fresh); });
  RecordingSink a, b, viewer;
  ASSERT_TRUE(streams.AttachDevice(&a, {"left", EffectSet::All()}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachDevice(&b, {"right", EffectSet::All()}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  streams.SetPose(&viewer, At(9), {9, 9});
  streams.SetPose(&a, At(1), {1, 10});
  streams.SetPose(&a, At(2), {2, 20});
  EXPECT_TRUE(told.empty());
  streams.SetPose(&b, At(3), {1, 30});
  EXPECT_EQ(told, std::vector<bool>{true});

  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(told.back(), false);
  ASSERT_EQ(fresh.taken().size(), 2u);
  EXPECT_EQ(fresh.taken()[0].first, "left");
  EXPECT_EQ(fresh.taken()[0].second.stamp.sequence, 2u);
  EXPECT_EQ(fresh.taken()[0].second.X_WD.translation().x(), 2);
  EXPECT_EQ(fresh.taken()[1].first, "right");
  streams.TakeFreshPoses(fresh);
  EXPECT_TRUE(fresh.taken().empty());

  told.clear();
  streams.SetPose(&a, At(4), {3, 40});
  EXPECT_TRUE(told.empty());  // "right" has not sent
  streams.Detach(&b);
  EXPECT_EQ(told, std::vector<bool>{true});
}

// A scene swap may go ahead only while every held tool stays; CloseAll
// ends every stream and refuses later attaches.
TEST(StreamRegistryTest, SwapsKeepHeldToolsAndCloseEnds) {
  StreamRegistry streams([](bool) {});
  RecordingSink device, viewer;
  ASSERT_TRUE(streams.AttachDevice(&device, {"probe", EffectSet::All()}, AnyTool).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  bool swapped = false;
  const absl::Status refused = streams.WhileToolsHeld(
      [](const std::string& tool) { return tool != "probe"; }, [&] { swapped = true; });
  EXPECT_EQ(refused.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_FALSE(swapped);
  EXPECT_TRUE(streams.WhileToolsHeld(AnyTool, [&] { swapped = true; }).ok());
  EXPECT_TRUE(swapped);

  streams.CloseAll(absl::UnavailableError("bye"));
  ASSERT_TRUE(device.closed_with.has_value());
  EXPECT_EQ(device.closed_with->code(), absl::StatusCode::kUnavailable);
  ASSERT_TRUE(viewer.closed_with.has_value());
  RecordingSink late;
  EXPECT_EQ(streams.AttachViewer(&late, EffectSet::All()).code(), absl::StatusCode::kUnavailable);
}

}  // namespace
}  // namespace hs
