#include "server/frame_message.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "tests/common/sim/pinch_rig.h"

namespace hs {
namespace {

// Two streams' identities (FillFrameMessage only compares them).
struct NoSink : FrameSink {
  void Offer(std::shared_ptr<const StepSnapshot>) override {}
  void Close(const absl::Status&) override {}
};

// What a device's stream has sent: its own tool's models only.
ModelsSent OwnToolOnly() {
  ModelsSent sent;
  sent.own_tool_only = true;
  return sent;
}

// A step of a scene of three objects whose tools 1 and 2 have local models
// of the revisions given, tool 1 held by `holder` as "alice".
std::shared_ptr<StepSnapshot> Snapshot(const FrameSink* holder, uint64_t revision_1,
                                       uint64_t revision_2,
                                       std::shared_ptr<const std::vector<std::string>> names) {
  auto s = std::make_shared<StepSnapshot>();
  s->step = 7;
  s->time_s = 0.007;
  s->names = std::move(names);
  for (const auto& [id, revision] : {std::pair{1, revision_1}, std::pair{2, revision_2}}) {
    ToolFrame tool;
    tool.tool = id;
    tool.local_model.revision = revision;
    tool.local_model.validity_radius_m = 0.01;
    tool.local_model.force_clamp_n = 10;
    s->frame.tools.push_back(tool);
  }
  s->applied = {AppliedPose{.sequence = 41, .device_time_ns = 99}, AppliedPose{}};
  auto holders = std::make_shared<ToolHolders>(3);
  (*holders)[1] = {holder, "alice"};
  s->holders = std::move(holders);
  return s;
}

// Frames name each held tool's holder; the holding stream's frames carry
// its last applied pose, by stream identity, not by name; a viewer's do
// not.
TEST(FrameMessageTest, HoldersAndTheDevicesLastPose) {
  NoSink device, viewer;
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"floor", "probe", "stylus"});
  const std::shared_ptr<StepSnapshot> s = Snapshot(&device, 1, 1, names);
  haptics::v1::Frame frame;
  ModelsSent sent;
  FillFrameMessage(*s, FrameParts{}, &device, 3, 5, sent, frame);
  EXPECT_EQ(frame.step(), 7);
  ASSERT_EQ(frame.tools_size(), 2);
  EXPECT_EQ(frame.tools(0).tool(), "probe");
  EXPECT_EQ(frame.tools(0).holder(), "alice");
  EXPECT_EQ(frame.tools(1).holder(), "");
  EXPECT_EQ(frame.last_pose_sequence(), 41u);
  EXPECT_EQ(frame.last_pose_device_time_ns(), 99);
  EXPECT_EQ(frame.dropped_frames(), 3u);
  EXPECT_EQ(frame.timings().sent_unix_ns(), 5);
  ModelsSent viewer_sent;
  FillFrameMessage(*s, FrameParts{}, &viewer, 0, 0, viewer_sent, frame);
  EXPECT_EQ(frame.tools(0).holder(), "alice");
  EXPECT_EQ(frame.last_pose_sequence(), 0u);
}

// A device stream's frames carry its own tool's state only (every tool's
// while its device holds none yet, so that a frame always has its tool);
// a viewer's carry every tool's.
TEST(FrameMessageTest, ADeviceGetsItsOwnToolOnly) {
  NoSink device, other, viewer;
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"floor", "probe", "stylus"});
  const std::shared_ptr<StepSnapshot> s = Snapshot(&device, 1, 1, names);
  s->frame.tools[0].force_W = Vector3d(0, 0, 1.5);
  haptics::v1::Frame frame;
  ModelsSent device_sent = OwnToolOnly(), other_sent = OwnToolOnly(), viewer_sent;
  FillFrameMessage(*s, FrameParts{}, &device, 0, 0, device_sent, frame);
  ASSERT_EQ(frame.tools_size(), 1);
  EXPECT_EQ(frame.tools(0).tool(), "probe");
  EXPECT_EQ(frame.tools(0).holder(), "alice");
  EXPECT_EQ(frame.tools(0).force_w_n().z(), 1.5);
  EXPECT_EQ(frame.tools(0).last_pose_sequence(), 41u);
  EXPECT_EQ(frame.last_pose_sequence(), 41u);
  FillFrameMessage(*s, FrameParts{}, &other, 0, 0, other_sent, frame);
  EXPECT_EQ(frame.tools_size(), 2);
  FillFrameMessage(*s, FrameParts{}, &viewer, 0, 0, viewer_sent, frame);
  EXPECT_EQ(frame.tools_size(), 2);
}

// Each local model revision goes to a stream once: a device stream gets its
// own tool's model only, a viewer every tool's; a newer revision goes out
// again, and so does every model of a new scene (new names table).
TEST(FrameMessageTest, EachModelRevisionGoesOutOnce) {
  NoSink device, viewer;
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"floor", "probe", "stylus"});
  ModelsSent device_sent = OwnToolOnly(), viewer_sent;
  haptics::v1::Frame frame;
  auto models = [&](const StepSnapshot& s, const FrameSink* stream, ModelsSent& sent) {
    FillFrameMessage(s, FrameParts{}, stream, 0, 0, sent, frame);
    std::vector<uint64_t> revisions;
    for (const haptics::v1::ToolState& t : frame.tools()) {
      revisions.push_back(t.has_local_model() ? t.local_model().revision() : 0);
    }
    return revisions;
  };
  EXPECT_EQ(models(*Snapshot(&device, 1, 1, names), &device, device_sent),
            (std::vector<uint64_t>{1}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 1, names), &viewer, viewer_sent),
            (std::vector<uint64_t>{1, 1}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 1, names), &device, device_sent),
            (std::vector<uint64_t>{0}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 2, names), &viewer, viewer_sent),
            (std::vector<uint64_t>{0, 2}));
  EXPECT_EQ(models(*Snapshot(&device, 2, 2, names), &device, device_sent),
            (std::vector<uint64_t>{2}));
  FrameParts no_models;
  no_models.local_model = false;
  FillFrameMessage(*Snapshot(&device, 3, 3, names), no_models, &device, 0, 0, device_sent, frame);
  EXPECT_FALSE(frame.tools(0).has_local_model());
  auto rebuilt = std::make_shared<const std::vector<std::string>>(*names);
  EXPECT_EQ(models(*Snapshot(&device, 2, 2, rebuilt), &device, device_sent),
            (std::vector<uint64_t>{2}));
}

// A surface's faces go to a stream once: the models after that share it
// by revision alone; a new surface's faces go out again, to each stream on
// its own, and so do a new scene's.
TEST(FrameMessageTest, EachSurfacesFacesGoOutOnce) {
  NoSink device, viewer;
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"floor", "probe", "stylus"});
  auto surface = [](uint64_t revision) {
    auto s = std::make_shared<ModelSurface>();
    s->revision = revision;
    s->radius_m = 0.01;
    s->tool_vertices_T = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()};
    s->tool_triangles = {{0, 1, 2}};
    return s;
  };
  ModelsSent device_sent = OwnToolOnly(), viewer_sent;
  haptics::v1::Frame frame;
  // Tool 1's model of `revision` with surface `surface_revision`: whether
  // its faces went out, and the surface revision named.
  auto faces = [&](uint64_t revision, uint64_t surface_revision, const FrameSink* stream,
                   ModelsSent& sent, std::shared_ptr<const std::vector<std::string>> table) {
    const std::shared_ptr<StepSnapshot> s = Snapshot(&device, revision, 0, table);
    s->frame.tools[0].local_model.surface = surface(surface_revision);
    FillFrameMessage(*s, FrameParts{}, stream, 0, 0, sent, frame);
    const haptics::v1::ModelSurface& got = frame.tools(0).local_model().surface();
    EXPECT_EQ(got.revision(), surface_revision);
    return got.tool_triangles_size() > 0;
  };
  EXPECT_TRUE(faces(1, 1, &device, device_sent, names));
  EXPECT_FALSE(faces(2, 1, &device, device_sent, names));
  EXPECT_FALSE(faces(3, 1, &device, device_sent, names));
  EXPECT_TRUE(faces(3, 1, &viewer, viewer_sent, names));
  EXPECT_TRUE(faces(4, 2, &device, device_sent, names));
  EXPECT_FALSE(faces(5, 2, &device, device_sent, names));
  auto rebuilt = std::make_shared<const std::vector<std::string>>(*names);
  EXPECT_TRUE(faces(5, 2, &device, device_sent, rebuilt));
}

// A snapshot of `scene`'s last step, `frame`, with no device holding a tool.
StepSnapshot SnapshotOf(const Scene& scene, const StepFrame& frame) {
  StepSnapshot s;
  s.frame = frame;
  auto names = std::make_shared<std::vector<std::string>>();
  for (ObjectId id = 0; id < scene.num_objects(); ++id) {
    names->push_back(scene.object(id).object.name());
  }
  s.names = std::move(names);
  s.applied.resize(frame.tools.size());
  return s;
}

// The frame's one body, the cube, after `frame`: its pose is the scene's
// own pose of the cube (to the quaternion's rounding), and it names the
// tools that touched it.
haptics::v1::BodyState CubeIn(const PinchRig& pinch, const StepFrame& frame) {
  NoSink viewer;
  ModelsSent sent;
  haptics::v1::Frame message;
  FillFrameMessage(SnapshotOf(*pinch.rig.scene, frame), FrameParts{}, &viewer, 0, 0, sent, message);
  EXPECT_EQ(message.bodies_size(), 1);
  if (message.bodies_size() != 1) return {};
  const haptics::v1::BodyState& cube = message.bodies(0);
  EXPECT_EQ(cube.name(), "cube");
  const absl::StatusOr<Isometry3d> X_WO = PoseFromProto(cube.pose(), "pose");
  EXPECT_TRUE(X_WO.ok());
  if (X_WO.ok()) {
    EXPECT_TRUE(X_WO->isApprox(pinch.rig.scene->object(pinch.cube).X_WO, 1e-12));
  }
  return cube;
}

// A free body's frame entry follows the scene: resting on the floor it is
// held by no tool; pinched and lifted 1 cm by two jaws it is held, by
// both, and its pose is the scene's own as it rises.
TEST(FrameMessageTest, FreeBodyPoseAndHolders) {
  PinchRig pinch = MakePinchRig(0.5);
  const haptics::v1::BodyState resting = CubeIn(pinch, *pinch.frame);
  EXPECT_FALSE(resting.held());
  EXPECT_EQ(resting.touching_tools_size(), 0);
  const double z0 = resting.pose().position_m().z();
  const haptics::v1::BodyState lifted = CubeIn(pinch, pinch.PinchAndLift());
  EXPECT_TRUE(lifted.held());
  EXPECT_EQ(
      std::vector<std::string>(lifted.touching_tools().begin(), lifted.touching_tools().end()),
      (std::vector<std::string>{"left", "right"}));
  EXPECT_GT(lifted.pose().position_m().z(), z0 + 0.0075);  // most of the 1 cm
}

// Jaws closed on a body that still rests on the floor touch it but do not
// hold it: the floor bears it too.
TEST(FrameMessageTest, PinchedOnTheFloorIsNotHeld) {
  PinchRig pinch = MakePinchRig(0.5);
  for (int i = 1; i <= 12; ++i) pinch.Drive(0.001 * i, 0);  // closing, not lifting
  const haptics::v1::BodyState pinched = CubeIn(pinch, *pinch.frame);
  EXPECT_FALSE(pinched.held());
  EXPECT_EQ(pinched.touching_tools_size(), 2);
}

// No bodies for a stream that does not need free-body motion, nor at a
// step whose free-body stage did not run (the bodies did not move).
TEST(FrameMessageTest, BodiesOnlyWhereNeededAndMoved) {
  PinchRig pinch = MakePinchRig(0.5);
  StepSnapshot s = SnapshotOf(*pinch.rig.scene, *pinch.frame);
  NoSink viewer;
  ModelsSent sent;
  haptics::v1::Frame message;
  FrameParts no_bodies;
  no_bodies.bodies = false;
  FillFrameMessage(s, no_bodies, &viewer, 0, 0, sent, message);
  EXPECT_EQ(message.bodies_size(), 0);
  s.frame.stages_run = s.frame.stages_run.Without(Effect::kFreeBodyMotion);
  FillFrameMessage(s, FrameParts{}, &viewer, 0, 0, sent, message);
  EXPECT_EQ(message.bodies_size(), 0);
}

}  // namespace
}  // namespace hs
