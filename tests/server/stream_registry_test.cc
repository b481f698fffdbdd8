#include "server/stream_registry.h"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <thread>
#include <vector>

namespace hs {
namespace {

// A stream; the registry never calls one (its ends are queued), so this
// one fails the test when it is called.
struct UncalledSink : FrameSink {
  void Offer(std::shared_ptr<const StepSnapshot>) override { ADD_FAILURE() << "offered"; }
  void Close(const absl::Status&) override { ADD_FAILURE() << "closed"; }
};

// A scene of four objects, two of them the tools "probe" (1) and "stylus" (3).
SceneTools Tools() { return {.tools = {{"probe", 1}, {"stylus", 3}}, .object_count = 4}; }

Isometry3d At(double x) {
  Isometry3d X = Isometry3d::Identity();
  X.translation().x() = x;
  return X;
}

// The ends queued since the last look.
std::vector<SinkEnd> Ends(StreamRegistry& streams) {
  std::vector<SinkEnd> ends;
  streams.TakeEnds(ends);
  return ends;
}

// Who holds each tool now, as a step takes it with the poses: tool id ->
// (stream, holder name).
std::map<ObjectId, ToolHolder> Holders(StreamRegistry& streams) {
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  std::map<ObjectId, ToolHolder> held;
  for (size_t id = 0; id < fresh.holders->size(); ++id) {
    if ((*fresh.holders)[id].sink != nullptr)
      held[static_cast<ObjectId>(id)] = (*fresh.holders)[id];
  }
  return held;
}

// A tool is held by one device at a time; a tool the scene lacks is
// NOT_FOUND; viewers attach freely; the counts say who is there.
TEST(StreamRegistryTest, ToolsAreHeldByOneDevice) {
  StreamRegistry streams(Tools());
  UncalledSink a, b, viewer;
  EXPECT_EQ(streams.AttachDevice(&a, {"missing", EffectSet::All()}).code(),
            absl::StatusCode::kNotFound);
  EXPECT_TRUE(streams.AttachDevice(&a, {"probe", EffectSet::All()}).ok());
  EXPECT_EQ(streams.AttachDevice(&b, {"probe", EffectSet::All()}).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  StreamRegistry::Counts counts = streams.counts();
  EXPECT_EQ(counts.devices, 1);
  EXPECT_EQ(counts.viewers, 1);
  EXPECT_EQ(counts.claimed_tools, std::vector<std::string>{"probe"});
  EXPECT_EQ(streams.Detach(&a).tool, "probe");
  EXPECT_EQ(streams.Detach(&viewer).tool, "");
  EXPECT_EQ(streams.Detach(&viewer).tool, std::nullopt);
  EXPECT_TRUE(streams.AttachDevice(&b, {"probe", EffectSet::All()}).ok());
  EXPECT_TRUE(Ends(streams).empty());
}

// Taking over a held tool queues the end of its device with the given
// status (the registry calls no stream), drops that device's pose not taken
// yet, and seats the new device on its first pose; the displaced device's
// later Detach finds nothing to free. A free tool is simply taken.
TEST(StreamRegistryTest, TakeOverQueuesTheHoldersEnd) {
  StreamRegistry streams(Tools());
  UncalledSink trainee, instructor, other;
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet::All()}).ok());
  streams.SetPose(&trainee, At(1), {1, 0});
  const absl::Status taken = absl::AbortedError("taken over");
  bool displaced = false;
  ASSERT_TRUE(
      streams.AttachDevice(&instructor, {"probe", EffectSet::All()}, &taken, &displaced).ok());
  EXPECT_TRUE(displaced);
  const std::vector<SinkEnd> ends = Ends(streams);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].sink, &trainee);
  EXPECT_EQ(ends[0].status, taken);
  EXPECT_TRUE(Ends(streams).empty());  // taken once
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.count, 0u);  // the trainee's pose went with it
  streams.SetPose(&instructor, At(2), {1, 0});
  streams.TakeFreshPoses(fresh);
  ASSERT_EQ(fresh.count, 1u);
  EXPECT_EQ(fresh.taken().front().first, 1);
  EXPECT_TRUE(fresh.taken().front().second.seat);
  EXPECT_EQ(streams.Detach(&trainee).tool, std::nullopt);
  EXPECT_EQ(streams.counts().claimed_tools, std::vector<std::string>{"probe"});
  displaced = false;
  ASSERT_TRUE(streams.AttachDevice(&other, {"stylus", EffectSet::All()}, &taken, &displaced).ok());
  EXPECT_FALSE(displaced);
  EXPECT_EQ(streams.AttachDevice(&other, {"missing", EffectSet::All()}, &taken).code(),
            absl::StatusCode::kNotFound);
}

// changes() moves with every stream that comes and every end queued (a
// take-over, a silent device, CloseAll), and not with poses or a stream
// that leaves: the fan-out then has nothing new to hand over.
TEST(StreamRegistryTest, ChangesCountComingsAndEnds) {
  StreamRegistry streams(Tools());
  UncalledSink trainee, instructor, viewer;
  uint64_t seen = streams.changes();
  const auto moved = [&] {
    const bool changed = streams.changes() != seen;
    seen = streams.changes();
    return changed;
  };
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet::All()}).ok());
  EXPECT_TRUE(moved());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  EXPECT_TRUE(moved());
  streams.SetPose(&trainee, At(1), {1, 0});
  EXPECT_FALSE(moved());
  const absl::Status taken = absl::AbortedError("taken over");
  ASSERT_TRUE(streams.AttachDevice(&instructor, {"probe", EffectSet::All()}, &taken).ok());
  EXPECT_TRUE(moved());
  streams.Detach(&trainee);
  EXPECT_FALSE(moved());
  std::vector<std::string> released;
  streams.EndSilentDevices(std::chrono::steady_clock::now() + std::chrono::seconds(1),
                           absl::UnavailableError("silent"), released);
  EXPECT_EQ(released, std::vector<std::string>{"probe"});
  EXPECT_TRUE(moved());
  streams.CloseAll(absl::UnavailableError("bye"));
  EXPECT_TRUE(moved());
}

// A stream that detaches before its queued end is handed over is not ended
// any more: nothing may call a stream that has left.
TEST(StreamRegistryTest, DetachDropsTheQueuedEnd) {
  StreamRegistry streams(Tools());
  UncalledSink trainee, instructor;
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet::All()}).ok());
  const absl::Status taken = absl::AbortedError("taken over");
  ASSERT_TRUE(streams.AttachDevice(&instructor, {"probe", EffectSet::All()}, &taken).ok());
  streams.Detach(&trainee);
  EXPECT_TRUE(Ends(streams).empty());
}

// Frames name each held tool's stream and holder, by tool id: the table
// follows attaches, take-overs and detaches, and a table taken before a
// change stays as it was.
TEST(StreamRegistryTest, HoldersFollowTheDevices) {
  StreamRegistry streams(Tools());
  UncalledSink trainee, instructor, viewer;
  EXPECT_TRUE(Holders(streams).empty());
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet(), "alice"}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet()).ok());
  FreshPoses before;
  streams.TakeFreshPoses(before);
  EXPECT_EQ(before.holders->size(), 4u);
  EXPECT_EQ((*before.holders)[1], (ToolHolder{&trainee, "alice"}));
  const absl::Status taken = absl::AbortedError("taken over");
  ASSERT_TRUE(streams.AttachDevice(&instructor, {"probe", EffectSet(), "dr.lee"}, &taken).ok());
  EXPECT_EQ(Holders(streams), (std::map<ObjectId, ToolHolder>{{1, {&instructor, "dr.lee"}}}));
  EXPECT_EQ((*before.holders)[1], (ToolHolder{&trainee, "alice"}));
  streams.Detach(&instructor);
  EXPECT_TRUE(Holders(streams).empty());
}

// A device not heard from since the cut-off is forgotten, its end queued
// with the status given and its tool released (listed, free for another
// device, its pose not taken yet dropped); a device heard from since, and
// viewers, stay.
TEST(StreamRegistryTest, SilentDevicesAreEnded) {
  StreamRegistry streams(Tools());
  UncalledSink silent, talking, viewer, next;
  ASSERT_TRUE(streams.AttachDevice(&silent, {"probe", EffectSet(), "a"}).ok());
  streams.SetPose(&silent, At(1), {1, 0});
  const auto cut_off = std::chrono::steady_clock::now() + std::chrono::nanoseconds(1);
  std::this_thread::sleep_until(cut_off + std::chrono::milliseconds(1));
  ASSERT_TRUE(streams.AttachDevice(&talking, {"stylus", EffectSet(), "b"}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet()).ok());
  std::vector<std::string> released;
  const absl::Status status = absl::DeadlineExceededError("silent");
  streams.EndSilentDevices(cut_off, status, released);
  EXPECT_EQ(released, std::vector<std::string>{"probe"});
  const std::vector<SinkEnd> ends = Ends(streams);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].sink, &silent);
  EXPECT_EQ(ends[0].status, status);
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.count, 0u);  // the silent device's pose went with it
  EXPECT_EQ(Holders(streams), (std::map<ObjectId, ToolHolder>{{3, {&talking, "b"}}}));
  // The stylus's pose now makes every device fresh.
  EXPECT_TRUE(streams.SetPose(&talking, At(2), {1, 0}).devices_fresh_since.has_value());
  EXPECT_TRUE(streams.AttachDevice(&next, {"probe", EffectSet(), "c"}).ok());
  released.clear();
  streams.EndSilentDevices(cut_off, status, released);
  EXPECT_TRUE(released.empty());
}

// A device's first pose seats it, also when a later pose replaces it before
// a step takes it; its later poses do not; the next device to take the tool
// is seated again.
TEST(StreamRegistryTest, ADevicesFirstPoseSeatsIt) {
  StreamRegistry streams(Tools());
  FreshPoses fresh;
  UncalledSink first, second;
  ASSERT_TRUE(streams.AttachDevice(&first, {"probe", EffectSet::All()}).ok());
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
  ASSERT_TRUE(streams.AttachDevice(&second, {"probe", EffectSet::All()}).ok());
  streams.SetPose(&second, At(4), {1, 0});
  EXPECT_TRUE(taken().seat);
}

// The scene computes the union of what the streams need.
TEST(StreamRegistryTest, NeedsAreTheUnion) {
  StreamRegistry streams(Tools());
  FreshPoses fresh;
  EXPECT_EQ(streams.TakeFreshPoses(fresh), EffectSet());
  UncalledSink device, viewer;
  ASSERT_TRUE(streams.AttachDevice(&device, {"probe", EffectSet{Effect::kForce}}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet{Effect::kContactSet}).ok());
  EXPECT_EQ(streams.TakeFreshPoses(fresh), (EffectSet{Effect::kForce, Effect::kContactSet}));
}

// "Every device has a fresh pose" is said, with the generation of the last
// take, by the last device's pose (or by the detach of the only silent
// device); each pose is taken once, in tool id order, the latest of a
// device winning; viewers' poses are ignored.
TEST(StreamRegistryTest, DevicesFreshOnceEveryDeviceSent) {
  StreamRegistry streams(Tools());
  UncalledSink a, b, viewer;
  ASSERT_TRUE(streams.AttachDevice(&a, {"stylus", EffectSet::All()}).ok());
  ASSERT_TRUE(streams.AttachDevice(&b, {"probe", EffectSet::All()}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.generation, 1u);
  EXPECT_FALSE(streams.SetPose(&viewer, At(9), {9, 9}).devices_fresh_since);
  EXPECT_FALSE(streams.SetPose(&a, At(1), {1, 10}).devices_fresh_since);
  EXPECT_FALSE(streams.SetPose(&a, At(2), {2, 20}).devices_fresh_since);
  EXPECT_EQ(streams.SetPose(&b, At(3), {1, 30}).devices_fresh_since, 1u);

  streams.TakeFreshPoses(fresh);
  EXPECT_EQ(fresh.generation, 2u);
  ASSERT_EQ(fresh.taken().size(), 2u);
  EXPECT_EQ(fresh.taken()[0].first, 1);  // probe
  EXPECT_EQ(fresh.taken()[1].first, 3);  // stylus
  EXPECT_EQ(fresh.taken()[1].second.stamp.sequence, 2u);
  EXPECT_EQ(fresh.taken()[1].second.X_WD.translation().x(), 2);
  streams.TakeFreshPoses(fresh);
  EXPECT_TRUE(fresh.taken().empty());

  EXPECT_FALSE(streams.SetPose(&a, At(4), {3, 40}).devices_fresh_since);  // b has not sent
  EXPECT_EQ(streams.Detach(&b).devices_fresh_since, 3u);
}

// A replacing scene takes the held tools to their new ids, with their poses
// not taken yet; one that lacks a held tool is refused and changes nothing.
// CloseAll queues every stream's end and refuses later attaches.
TEST(StreamRegistryTest, RemapFollowsHeldToolsAndCloseEnds) {
  StreamRegistry streams(Tools());
  UncalledSink device, viewer;
  ASSERT_TRUE(streams.AttachDevice(&device, {"probe", EffectSet::All()}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  streams.SetPose(&device, At(5), {7, 0});
  EXPECT_EQ(streams.RemapTools({.tools = {{"stylus", 0}}, .object_count = 2}).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(Holders(streams).count(1), 1u);  // unchanged; the pose was taken here
  streams.SetPose(&device, At(6), {8, 0});
  ASSERT_TRUE(streams.RemapTools({.tools = {{"stylus", 0}, {"probe", 5}}, .object_count = 6}).ok());
  FreshPoses fresh;
  streams.TakeFreshPoses(fresh);
  ASSERT_EQ(fresh.count, 1u);
  EXPECT_EQ(fresh.taken()[0].first, 5);
  EXPECT_EQ(fresh.taken()[0].second.stamp.sequence, 8u);
  EXPECT_EQ((*fresh.holders)[5].sink, &device);
  EXPECT_EQ(streams.counts().claimed_tools, std::vector<std::string>{"probe"});

  streams.CloseAll(absl::UnavailableError("bye"));
  const std::vector<SinkEnd> ends = Ends(streams);
  ASSERT_EQ(ends.size(), 2u);
  for (const SinkEnd& end : ends) EXPECT_EQ(end.status.code(), absl::StatusCode::kUnavailable);
  UncalledSink late;
  EXPECT_EQ(streams.AttachViewer(&late, EffectSet::All()).code(), absl::StatusCode::kUnavailable);
}

}  // namespace
}  // namespace hs
