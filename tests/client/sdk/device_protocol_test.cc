#include "client/sdk/device_protocol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "common/api/local_model_convert.h"

namespace hs::sdk {
namespace {

namespace pb = haptics::v1;

DeviceConfig Config(bool local_model = true) {
  DeviceConfig config{.scene = "demo", .tool = "probe"};
  config.options.local_model = local_model;
  return config;
}

PoseSample Sample(double x, int64_t time_ns, int64_t beyond_validity_ticks = 0) {
  PoseSample sample;
  sample.position_m[0] = x;
  sample.position_m[2] = 0.25;
  sample.orientation_wxyz[0] = std::sqrt(0.5);
  sample.orientation_wxyz[3] = std::sqrt(0.5);
  sample.time_ns = time_ns;
  sample.beyond_validity_ticks = beyond_validity_ticks;
  return sample;
}

// A frame that applied pose `sequence`, sent at `device_time_ns`, with the
// state of `tool`.
pb::Frame FrameFor(const std::string& tool, uint64_t sequence, int64_t device_time_ns) {
  pb::Frame frame;
  frame.set_last_pose_sequence(sequence);
  frame.set_last_pose_device_time_ns(device_time_ns);
  frame.add_tools()->set_tool(tool);
  return frame;
}

LocalModel Model(uint64_t revision) {
  LocalModel model;
  model.revision = revision;
  model.validity_radius_m = 0.01;
  model.force_clamp_n = 5;
  return model;
}

TEST(DeviceProtocolTest, OpenAsksForWhatTheDeviceRenders) {
  DeviceConfig config = Config();
  config.options.rate_hz = 200;
  config.options.take_over = true;
  config.extra_needs = {pb::EFFECT_CONTACT_SET};
  const pb::InteractRequest::Open open = DeviceProtocol(config).Open();
  EXPECT_EQ(open.scene(), "demo");
  EXPECT_EQ(open.tool(), "probe");
  EXPECT_TRUE(open.take_over());
  EXPECT_EQ(open.frame_rate_hz(), 200);  // 0: as poses go
  ASSERT_EQ(open.needs_size(), 4);
  EXPECT_EQ(open.needs(0), pb::EFFECT_FORCE);
  EXPECT_EQ(open.needs(1), pb::EFFECT_FRICTION);
  EXPECT_EQ(open.needs(2), pb::EFFECT_LOCAL_MODEL);
  EXPECT_EQ(open.needs(3), pb::EFFECT_CONTACT_SET);
  EXPECT_TRUE(open.surface_only()) << "the loop reads a model's surface alone";

  DeviceConfig force_only = Config(false);
  force_only.options.frame_rate_hz = 500;
  const pb::InteractRequest::Open plain = DeviceProtocol(force_only).Open();
  EXPECT_EQ(plain.frame_rate_hz(), 500);
  ASSERT_EQ(plain.needs_size(), 2);
  EXPECT_EQ(plain.needs(1), pb::EFFECT_FRICTION);
  EXPECT_FALSE(plain.surface_only());
}

TEST(DeviceProtocolTest, PosesCountFromOneOnEachStreamAndCarryTheSample) {
  const DeviceConfig config = Config();
  DeviceProtocol protocol(config);
  protocol.Begin(1);
  pb::InteractRequest request;
  for (uint64_t n = 1; n <= 3; ++n) {
    protocol.PoseRequest(Sample(0.001 * n, 1000 * n), request);
    EXPECT_EQ(request.pose().sequence(), n);
  }
  const pb::ToolPose& pose = request.pose();
  EXPECT_EQ(pose.device_time_ns(), 3000);
  EXPECT_EQ(pose.pose().position_m().x(), 0.003);
  EXPECT_EQ(pose.pose().position_m().z(), 0.25);
  EXPECT_EQ(pose.pose().orientation().w(), std::sqrt(0.5));
  EXPECT_EQ(pose.pose().orientation().z(), std::sqrt(0.5));
  protocol.Begin(2);
  protocol.PoseRequest(Sample(0, 4000), request);
  EXPECT_EQ(request.pose().sequence(), 1u);
}

TEST(DeviceProtocolTest, PosesAskForTheModelAsAModelRequesterSays) {
  // The oracle: a ModelRequester fed the same positions, counts and round
  // trips (the longest read since the last pose); and before the stream's
  // first model every pose asks for one.
  const DeviceConfig config = Config();
  DeviceProtocol protocol(config);
  ModelRequester oracle;
  protocol.Begin(1);
  pb::InteractRequest request;
  const int64_t ms = 1'000'000;
  int64_t beyond = 0;
  for (int k = 1; k <= 40; ++k) {
    if (k % 7 == 0) beyond += 3;
    const int64_t t = k * 4 * ms;
    if (k > 10) {
      // Frames applying the pose of 10 ms and 30 ms ago: 30 ms is the peak.
      // The first of them brings the stream's first model.
      pb::Frame frame = FrameFor("probe", k - 3, t - 10 * ms);
      if (k == 11) LocalModelToProto(Model(1), {}, frame.mutable_tools(0)->mutable_local_model());
      EXPECT_EQ(protocol.Read(frame, t).new_model, k == 11);
      protocol.Read(FrameFor("probe", k - 8, t - 30 * ms), t);
      oracle.AddRoundTrip(static_cast<double>(t) * 1e-9, 0.030);
    }
    const PoseSample sample = Sample(0.002 * k, t, beyond);
    protocol.PoseRequest(sample, request);
    const ModelRequest expected =
        oracle.ForPose(static_cast<double>(t) * 1e-9, Vector3d(0.002 * k, 0, 0.25), beyond);
    // Until the first model came, every pose asks for one.
    EXPECT_EQ(request.pose().model_stale(), expected.model_stale || k <= 10) << k;
    EXPECT_EQ(request.pose().validity_radius_m(), expected.validity_radius_m) << k;
  }
  // Without the local model a pose asks nothing of it.
  const DeviceConfig plain_config = Config(false);
  DeviceProtocol plain(plain_config);
  plain.Begin(1);
  plain.PoseRequest(Sample(0, 1000, 5), request);
  EXPECT_FALSE(request.pose().model_stale());
  EXPECT_EQ(request.pose().validity_radius_m(), 0);
}

// A surface's faces come once, in the model that brings them; the models
// after it that name the surface alone get those faces in the feed, so the
// loop has them even if it never took the model that brought them.
TEST(DeviceProtocolTest, ModelsNamingASurfaceGetItsFaces) {
  const DeviceConfig config = Config();
  DeviceProtocol protocol(config);
  protocol.Begin(3);
  pb::InteractRequest request;
  protocol.PoseRequest(Sample(0, 1000), request);
  auto surface = std::make_shared<ModelSurface>();
  surface->revision = 4;
  surface->radius_m = 0.015;
  surface->tool_vertices_T = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()};
  surface->tool_triangles = {{0, 1, 2}};
  LocalModel model = Model(1);
  model.surface = surface;
  auto read_model = [&](uint64_t revision, bool faces) {
    model.revision = revision;
    pb::Frame frame = FrameFor("probe", 1, 1000);
    LocalModelToProto(model, {}, frame.mutable_tools(0)->mutable_local_model(), faces);
    EXPECT_TRUE(protocol.Read(frame, 2000).new_model);
    return protocol.feed().model.surface;
  };
  EXPECT_TRUE(read_model(1, true)->has_body());
  EXPECT_TRUE(read_model(2, false)->has_body());
  EXPECT_TRUE(read_model(3, false)->has_body());
  surface->revision = 5;
  EXPECT_FALSE(read_model(4, false)->has_body()) << "a surface it never got";
  // Surfaces are kept across streams (the tick may still hold one), and
  // matched by centre and radius too: a rebuilt scene numbers its
  // surfaces from 1 again.
  protocol.Begin(4);
  protocol.PoseRequest(Sample(0, 1000), request);
  surface->revision = 4;
  EXPECT_TRUE(read_model(5, false)->has_body());
  surface->center_W.x() = 0.5;
  EXPECT_FALSE(read_model(6, false)->has_body()) << "another scene's surface 4";
}

TEST(DeviceProtocolTest, FramesConnectAndBringEachModelOnce) {
  const DeviceConfig config = Config();
  DeviceProtocol protocol(config);
  protocol.Begin(3);
  EXPECT_FALSE(protocol.feed().connected);

  // The tool's last device's pose (sequence 40, at 100 ns): none of this
  // stream's, and neither is the model built for it.
  pb::Frame not_ours = FrameFor("probe", 40, 100);
  LocalModelToProto(Model(5), {}, not_ours.mutable_tools(0)->mutable_local_model());
  FrameRead read = protocol.Read(not_ours, 500);
  EXPECT_TRUE(read.first_frame);
  EXPECT_TRUE(read.feed_changed);
  EXPECT_EQ(read.applied_sequence, 0u);
  EXPECT_EQ(read.round_trip_ns, -1);
  EXPECT_FALSE(read.new_model);
  EXPECT_TRUE(protocol.feed().connected);
  EXPECT_EQ(protocol.feed().stream, 3u);
  EXPECT_EQ(protocol.feed().model_serial, 0u);
  pb::InteractRequest request;
  protocol.PoseRequest(Sample(0, 600), request);
  protocol.PoseRequest(Sample(0, 1000), request);
  // Sequence 2 but older than this stream's first pose; sequence 3 not
  // sent yet: neither is this stream's.
  EXPECT_EQ(protocol.Read(FrameFor("probe", 2, 100), 700).applied_sequence, 0u);
  EXPECT_EQ(protocol.Read(FrameFor("probe", 3, 1000), 1100).round_trip_ns, -1);

  pb::Frame with_model = FrameFor("probe", 2, 1000);
  LocalModelToProto(Model(7), {}, with_model.mutable_tools(0)->mutable_local_model());
  read = protocol.Read(with_model, 4000);
  EXPECT_FALSE(read.first_frame);
  EXPECT_TRUE(read.new_model);
  EXPECT_EQ(read.applied_sequence, 2u);
  EXPECT_EQ(read.round_trip_ns, 3000);
  EXPECT_EQ(protocol.feed().model_serial, 1u);
  EXPECT_EQ(protocol.feed().model_stream, 3u);
  EXPECT_EQ(protocol.feed().model.revision, 7u);

  // The same revision again, another tool's model, a model that fails the
  // checks: nothing new.
  read = protocol.Read(with_model, 5000);
  EXPECT_FALSE(read.new_model);
  EXPECT_FALSE(read.feed_changed);
  pb::Frame other = FrameFor("forceps", 2, 1000);
  LocalModelToProto(Model(9), {}, other.mutable_tools(0)->mutable_local_model());
  EXPECT_FALSE(protocol.Read(other, 5000).new_model);
  protocol.PoseRequest(Sample(0, 2000), request);
  pb::Frame broken = FrameFor("probe", 3, 2000);
  LocalModel bad = Model(8);
  LocalModelToProto(bad, {}, broken.mutable_tools(0)->mutable_local_model());
  broken.mutable_tools(0)->mutable_local_model()->set_validity_radius_m(NAN);
  read = protocol.Read(broken, 6000);
  EXPECT_TRUE(read.model_rejected);
  EXPECT_FALSE(read.new_model);
  EXPECT_EQ(protocol.feed().model.revision, 7u);

  protocol.End();
  EXPECT_FALSE(protocol.feed().connected);
  // A new stream takes a model of a revision seen on the last one, once it
  // applied the new stream's poses.
  protocol.Begin(4);
  EXPECT_FALSE(protocol.Read(with_model, 7000).new_model);
  protocol.PoseRequest(Sample(0, 900), request);
  protocol.PoseRequest(Sample(0, 1000), request);
  EXPECT_TRUE(protocol.Read(with_model, 7000).new_model);
  EXPECT_EQ(protocol.feed().model_stream, 4u);
}

TEST(DeviceProtocolTest, WithoutTheLocalModelEachFrameBringsTheForce) {
  // Each frame read goes on to config.on_frame with what was read there.
  DeviceConfig config = Config(false);
  std::vector<uint64_t> seen;
  config.on_frame = [&](const pb::Frame& frame, const FrameRead& read) {
    EXPECT_EQ(frame.last_pose_sequence(), read.applied_sequence);
    seen.push_back(read.applied_sequence);
  };
  DeviceProtocol protocol(config);
  protocol.Begin(1);
  pb::InteractRequest request;
  protocol.PoseRequest(Sample(0, 1000), request);
  pb::Frame frame = FrameFor("probe", 1, 1000);
  pb::Vector3* force = frame.mutable_tools(0)->mutable_force_w_n();
  force->set_x(0.5);
  force->set_z(-2);
  LocalModelToProto(Model(7), {}, frame.mutable_tools(0)->mutable_local_model());
  FrameRead read = protocol.Read(frame, 2000);
  EXPECT_TRUE(read.feed_changed);
  EXPECT_FALSE(read.new_model);
  EXPECT_EQ(protocol.feed().force_n[0], 0.5);
  EXPECT_EQ(protocol.feed().force_n[2], -2);
  // A force that is not finite is none.
  force->set_y(INFINITY);
  protocol.Read(frame, 3000);
  for (double f : protocol.feed().force_n) EXPECT_EQ(f, 0);
  EXPECT_EQ(seen, (std::vector<uint64_t>{1, 1}));
}

}  // namespace
}  // namespace hs::sdk
