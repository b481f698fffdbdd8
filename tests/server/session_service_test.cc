#include "server/session_service.h"

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <thread>
#include <vector>

#include "client/tool_path.h"
#include "common/api/proto_convert.h"
#include "common/api/scene_file.h"
#include "tests/common/test_data_dir.h"
#include "tests/server/test_server.h"

namespace hs::testing {
namespace {

using google::protobuf::util::MessageDifferencer;
const std::string kScenes = hs::ScenesDir();

// A device on an Interact stream, driven from the test thread.
class Device {
 public:
  Device(TestServer& server, const std::string& scene, const std::string& tool,
         std::vector<pb::Effect> needs = {}, bool surface_only = false)
      : context_(ContextWithin(60)), stream_(server.sessions().Interact(context_.get())) {
    pb::InteractRequest open;
    open.mutable_open()->set_scene(scene);
    open.mutable_open()->set_tool(tool);
    open.mutable_open()->set_surface_only(surface_only);
    for (pb::Effect e : needs) open.mutable_open()->add_needs(e);
    stream_->Write(open);
  }
  bool Send(uint64_t sequence, const pb::Pose& pose, double validity_radius_m = 0) {
    pb::InteractRequest request;
    request.mutable_pose()->set_sequence(sequence);
    *request.mutable_pose()->mutable_pose() = pose;
    request.mutable_pose()->set_validity_radius_m(validity_radius_m);
    return stream_->Write(request);
  }
  // The first frame that carries pose `sequence`; false when the stream ends.
  bool ReadUntil(uint64_t sequence, pb::Frame& frame) {
    while (stream_->Read(&frame)) {
      if (frame.last_pose_sequence() >= sequence) return true;
    }
    return false;
  }
  bool Read(pb::Frame& frame) { return stream_->Read(&frame); }
  grpc::Status Finish() {
    stream_->WritesDone();
    pb::Frame frame;
    while (stream_->Read(&frame)) {
    }
    return stream_->Finish();
  }
  grpc::ClientContext& context() { return *context_; }

 private:
  std::unique_ptr<grpc::ClientContext> context_;
  std::unique_ptr<grpc::ClientReaderWriter<pb::InteractRequest, pb::Frame>> stream_;
};

pb::Pose ToPose(const Isometry3d& X) {
  pb::Pose pose;
  PoseToProto(X, &pose);
  return pose;
}

// A device driving the demo tool into the organ pose by pose: every step's
// frame holds the tools' contents that the same poses give offline through
// hs::Scene (contacts, reversing vectors, proxy, force: all of it). A viewer
// sees every step (its queue drops none here), and each step's device pose
// says which of the path's poses the offline scene takes at that step: the
// server steps on between poses, and a step right after a move differs
// from the move's (no device velocity for the damper), so the steps are
// matched one for one, not pose for pose.
TEST(SessionServiceTest, DeviceFramesEqualOfflineScene) {
  TestServer server;
  const std::string file = kScenes + "/probe_on_torus.textproto";
  absl::StatusOr<pb::SceneSpec> spec = ReadSceneFile(file);
  ASSERT_TRUE(spec.ok()) << spec.status();
  ASSERT_TRUE(server.server().registry().Create(*spec, kScenes).ok());
  absl::StatusOr<std::vector<Isometry3d>> path =
      cli::ReadToolPath(kScenes + "/press_and_slide.csv");
  ASSERT_TRUE(path.ok());
  absl::StatusOr<LoadedScene> offline = LoadSceneFile(file);
  ASSERT_TRUE(offline.ok());

  auto viewer_context = ContextWithin(60);
  pb::WatchRequest watch;
  watch.set_scene(spec->name());
  auto viewer = server.sessions().Watch(viewer_context.get(), watch);
  std::vector<pb::Frame> seen;
  pb::Frame first;
  ASSERT_TRUE(viewer->Read(&first));  // attached before the device moves
  seen.push_back(first);
  std::thread watching([&] {
    pb::Frame frame;
    while (viewer->Read(&frame)) seen.push_back(frame);
  });
  Device device(server, spec->name(), "probe");
  for (size_t i = 0; i < path->size(); ++i) {
    ASSERT_TRUE(device.Send(i + 1, ToPose((*path)[i])));
    pb::Frame frame;
    ASSERT_TRUE(device.ReadUntil(i + 1, frame));
    EXPECT_EQ(frame.tools(0).holder(), "peer:127.0.0.1");  // who holds it: this test
  }
  EXPECT_TRUE(device.Finish().ok());
  viewer_context->TryCancel();
  watching.join();
  viewer->Finish();

  size_t k = 0;  // the path pose the device is at
  bool moved = false;
  int with_contacts = 0;
  for (size_t n = 0; n < seen.size(); ++n) {
    pb::Frame& frame = seen[n];
    ASSERT_EQ(frame.dropped_frames(), 0u) << "the viewer missed steps";
    if (n > 0) {
      ASSERT_EQ(frame.step(), seen[n - 1].step() + 1);
    }
    for (size_t j = moved ? k : 0; j < path->size(); ++j) {
      if (MessageDifferencer::Equals(frame.tools(0).device_pose(), ToPose((*path)[j]))) {
        k = j;
        moved = true;
        break;
      }
    }
    if (moved) {
      ASSERT_TRUE(offline->scene->SetDevicePose(offline->tools.front(), (*path)[k]).ok());
    }
    pb::Frame expected;
    StepFrameToProto(offline->scene->Step(), offline->names, FrameParts{}, &expected);
    ASSERT_EQ(frame.tools_size(), expected.tools_size());
    frame.mutable_tools(0)->clear_holder();
    for (int t = 0; t < frame.tools_size(); ++t) {
      // The server adds each tool's last applied pose, which offline has none of.
      frame.mutable_tools(t)->clear_last_pose_sequence();
      frame.mutable_tools(t)->clear_last_pose_device_time_ns();
      EXPECT_TRUE(MessageDifferencer::Equals(frame.tools(t), expected.tools(t)))
          << "step " << frame.step() << " at pose " << k + 1
          << "\nserver:  " << frame.tools(t).ShortDebugString()
          << "\noffline: " << expected.tools(t).ShortDebugString();
    }
    with_contacts += frame.tools(0).contacts_size() > 0;
  }
  EXPECT_TRUE(moved);
  EXPECT_GT(with_contacts, 10);
}

// Two devices (each its own tool) and a viewer in one scene receive the
// same frames: every step id seen by more than one stream carries the same
// state of each tool, and the streams overlap on most steps. A device's
// frames carry its own tool only from the first step that names it the
// tool's holder; the viewer's every tool.
TEST(SessionServiceTest, TwoDevicesAndViewerSeeTheSameSteps) {
  TestServer server;
  server.Create(SmallScene("shared", /*second_tool=*/true));
  auto viewer_context = ContextWithin(30);
  pb::WatchRequest watch;
  watch.set_scene("shared");
  auto viewer = server.sessions().Watch(viewer_context.get(), watch);
  Device a(server, "shared", "probe");
  Device b(server, "shared", "stylus");

  // Per stream, per step: each tool's state, serialized, by tool name.
  std::map<int64_t, std::map<std::string, std::string>> seen[3];
  auto collect = [&](int who, auto read) {
    pb::Frame frame;
    for (int n = 0; n < 200 && read(frame); ++n) {
      std::map<std::string, std::string> tools;
      for (const auto& t : frame.tools()) tools[t.tool()] = t.SerializeAsString();
      if (!seen[who].empty()) {
        EXPECT_GT(frame.step(), seen[who].rbegin()->first);
      }
      seen[who][frame.step()] = tools;
    }
  };
  std::thread moves([&] {
    for (int i = 1; i <= 100; ++i) {
      a.Send(i, PoseAt(0, 0, 0.05 - 0.0004 * i));
      b.Send(i, PoseAt(0.05, 0, 0.05 - 0.0004 * i));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  std::thread ta([&] { collect(0, [&](pb::Frame& f) { return a.Read(f); }); });
  std::thread tb([&] { collect(1, [&](pb::Frame& f) { return b.Read(f); }); });
  collect(2, [&](pb::Frame& f) { return viewer->Read(&f); });
  moves.join();
  ta.join();
  tb.join();

  const std::string own[2] = {"probe", "stylus"};
  int64_t first_own_only[2];
  for (int who = 0; who < 2; ++who) {
    const auto own_only = std::find_if(seen[who].begin(), seen[who].end(),
                                       [](const auto& entry) { return entry.second.size() == 1u; });
    ASSERT_NE(own_only, seen[who].end()) << "device " << who << " never held its tool";
    first_own_only[who] = own_only->first;
  }
  int common = 0;
  for (const auto& [step, tools] : seen[2]) {
    EXPECT_EQ(tools.size(), 2u) << "step " << step;
    for (int who = 0; who < 2; ++who) {
      const auto it = seen[who].find(step);
      if (it == seen[who].end()) continue;
      ++common;
      ASSERT_TRUE(it->second.contains(own[who])) << "step " << step;
      if (it->second.size() != 1u) {
        // Until a step names the device its tool's holder, its frames carry
        // every tool, as a viewer's; never after.
        pb::ToolState own_state;
        ASSERT_TRUE(own_state.ParseFromString(it->second.at(own[who])));
        EXPECT_EQ(own_state.holder(), "") << "step " << step;
        EXPECT_LT(step, first_own_only[who]) << "step " << step;
      }
      EXPECT_EQ(it->second.at(own[who]), tools.at(own[who])) << "step " << step;
    }
  }
  // Device streams are latest-wins, so on a loaded machine they skip steps.
  EXPECT_GT(common, 40);
  viewer_context->TryCancel();
  viewer->Finish();
  EXPECT_TRUE(a.Finish().ok());
  EXPECT_TRUE(b.Finish().ok());
}

// A second device claiming a held tool is refused (FAILED_PRECONDITION);
// once the first device cancels mid-stream the tool is free again.
// A device that says it reads the surface alone (Open.surface_only) gets
// models with the surface's faces and no planes; one that does not, the
// planes too. The probe rests on the table.
TEST(SessionServiceTest, ADeviceThatReadsTheSurfaceAloneGetsNoPlanes) {
  TestServer server;
  for (const bool surface_only : {true, false}) {
    const std::string name = surface_only ? "alone" : "planes";
    server.Create(SmallScene(name));
    Device device(server, name, "probe", {pb::EFFECT_FORCE, pb::EFFECT_LOCAL_MODEL}, surface_only);
    ASSERT_TRUE(device.Send(1, PoseAt(0, 0, 0.0195)));
    pb::Frame frame;
    ASSERT_TRUE(device.ReadUntil(1, frame));
    ASSERT_EQ(frame.tools_size(), 1);
    const pb::LocalModel& model = frame.tools(0).local_model();
    EXPECT_TRUE(model.touching()) << name;
    EXPECT_GT(model.surface().triangles_size(), 0) << name;
    EXPECT_EQ(model.planes_size() == 0, surface_only) << name;
    EXPECT_TRUE(device.Finish().ok()) << name;
  }
}

TEST(SessionServiceTest, ToolHeldUntilCancelled) {
  TestServer server;
  server.Create(SmallScene("claim"));
  Device first(server, "claim", "probe");
  pb::Frame frame;
  ASSERT_TRUE(first.Read(frame));
  Device second(server, "claim", "probe");
  EXPECT_EQ(second.Finish().error_code(), grpc::StatusCode::FAILED_PRECONDITION);

  first.context().TryCancel();
  EXPECT_EQ(first.Finish().error_code(), grpc::StatusCode::CANCELLED);
  // The server lets go of the tool when the cancelled stream is done.
  bool claimed = false;
  for (int attempt = 0; attempt < 200 && !claimed; ++attempt) {
    Device third(server, "claim", "probe");
    claimed = third.Read(frame);
    third.Finish();
    if (!claimed) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(claimed);
}

// A viewer that stops reading loses frames without stopping the scene or a
// reading device: the device keeps getting frames as steps go on, and
// the stalled viewer, once it reads again, is told how many it lost.
TEST(SessionServiceTest, StalledViewerDropsFramesOthersKeepPace) {
  TestServer server;
  server.Create(SmallScene("stall"));
  // The viewer's own connection, with small fixed flow-control windows, so
  // that transport buffers fill after a few frames instead of megabytes.
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  args.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 1024);
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  auto stub = pb::SessionService::NewStub(
      grpc::CreateCustomChannel(server.address(), grpc::InsecureChannelCredentials(), args));
  auto viewer_context = ContextWithin(30);
  pb::WatchRequest watch;
  watch.set_scene("stall");
  auto viewer = stub->Watch(viewer_context.get(), watch);
  pb::Frame frame;
  ASSERT_TRUE(viewer->Read(&frame));
  const int64_t first_step = frame.step();

  Device device(server, "stall", "probe");
  ASSERT_TRUE(device.Read(frame));
  const int64_t start_step = frame.step();
  const auto start = std::chrono::steady_clock::now();
  int frames = 0;
  std::vector<double> start_lag_ms;  // the device's steps: how late each started
  // Moving the tool makes each frame carry contacts: bigger frames fill the
  // stalled viewer's transport buffers sooner.
  for (int i = 1; std::chrono::steady_clock::now() - start < std::chrono::milliseconds(1500); ++i) {
    device.Send(i, PoseAt(0, 0, 0.0195 - 1e-6 * (i % 100)));
    ASSERT_TRUE(device.Read(frame));
    start_lag_ms.push_back(static_cast<double>(frame.timings().start_lag_ns()) / 1e6);
    ++frames;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double steps = static_cast<double>(frame.step() - start_step);
  // 1 kHz on an idle machine. A scene held up by the stalled viewer would
  // stop once the viewer's buffers are full; the bound only tells "goes
  // on" from "stopped", since other builds may share the 2 cores. That the
  // viewer is told of drops below is the direct proof that the scene did
  // not wait for it.
  EXPECT_GT(steps / seconds, 50);
  EXPECT_GT(frames, 50);
  // The device's step jitter while the viewer is stalled, recorded in the
  // test report (measured: see docs/server.md). The bound only says the
  // scene never waited on the viewer for long: a wait for its buffers to
  // drain would last as long as the viewer stalls (seconds).
  std::sort(start_lag_ms.begin(), start_lag_ms.end());
  const double p50 = start_lag_ms[start_lag_ms.size() / 2];
  const double p99 = start_lag_ms[start_lag_ms.size() * 99 / 100];
  RecordProperty("device_start_lag_p50_ms", std::to_string(p50));
  RecordProperty("device_start_lag_p99_ms", std::to_string(p99));
  std::printf("device step start lag with a stalled viewer: p50 %.3f ms, p99 %.3f ms\n", p50, p99);
  EXPECT_LT(p99, 500);

  uint64_t dropped = 0;
  int64_t last_step = first_step;
  for (int n = 0; n < 500 && viewer->Read(&frame); ++n) {
    EXPECT_GT(frame.step(), last_step);
    last_step = frame.step();
    dropped = frame.dropped_frames();
  }
  EXPECT_GT(dropped, 0u);
  viewer_context->TryCancel();
  viewer->Finish();
  device.Finish();
}

// Shutting the server down mid-stream ends device and viewer streams with
// UNAVAILABLE after they got frames, and later calls find no server.
TEST(SessionServiceTest, ShutdownMidStreamEndsStreamsUnavailable) {
  TestServer server;
  server.Create(SmallScene("bye"));
  Device device(server, "bye", "probe");
  auto viewer_context = ContextWithin(30);
  pb::WatchRequest watch;
  watch.set_scene("bye");
  auto viewer = server.sessions().Watch(viewer_context.get(), watch);
  pb::Frame frame;
  ASSERT_TRUE(device.Read(frame));
  ASSERT_TRUE(viewer->Read(&frame));

  std::thread stop([&] { server.server().Shutdown(2.0); });
  int device_frames = 0;
  while (device.Read(frame)) ++device_frames;
  EXPECT_EQ(device.Finish().error_code(), grpc::StatusCode::UNAVAILABLE);
  while (viewer->Read(&frame)) {
  }
  EXPECT_EQ(viewer->Finish().error_code(), grpc::StatusCode::UNAVAILABLE);
  stop.join();
  EXPECT_GT(device_frames, 0);
}

// The stages a scene runs are the union of what its streams need: a
// collision-only device with a poses-only viewer runs collision alone; a
// contacts viewer joining adds the contact set and reversing vector but
// not the force, and it receives contacts but no forces.
TEST(SessionServiceTest, StagesAreTheUnionOfStreamNeeds) {
  TestServer server;
  server.Create(SmallScene("needs"));
  Device device(server, "needs", "probe", {pb::EFFECT_COLLISION});
  auto watch_context = ContextWithin(30);
  pb::WatchRequest watch;
  watch.set_scene("needs");
  watch.add_parts(pb::WATCH_PART_POSES);
  auto poses_viewer = server.sessions().Watch(watch_context.get(), watch);
  pb::Frame frame;
  ASSERT_TRUE(poses_viewer->Read(&frame));

  auto stages_after_move = [&](uint64_t sequence) {
    device.Send(sequence, PoseAt(0, 0, 0.0195 - 1e-5 * static_cast<double>(sequence)));
    EXPECT_TRUE(device.ReadUntil(sequence, frame));
    std::set<int> stages(frame.stages_run().begin(), frame.stages_run().end());
    return stages;
  };
  EXPECT_EQ(stages_after_move(1),
            (std::set<int>{pb::EFFECT_COLLISION, pb::EFFECT_CONTINUOUS_COLLISION}));
  EXPECT_EQ(frame.tools(0).contacts_size(), 1);

  auto contacts_context = ContextWithin(30);
  watch.set_parts(0, pb::WATCH_PART_CONTACTS);
  auto contacts_viewer = server.sessions().Watch(contacts_context.get(), watch);
  ASSERT_TRUE(contacts_viewer->Read(&frame));
  EXPECT_EQ(stages_after_move(2),
            (std::set<int>{pb::EFFECT_COLLISION, pb::EFFECT_CONTINUOUS_COLLISION,
                           pb::EFFECT_CONTACT_SET, pb::EFFECT_REVERSING_VECTOR}));
  const int64_t moved_step = frame.step();
  while (contacts_viewer->Read(&frame) && frame.step() < moved_step) {
  }
  ASSERT_EQ(frame.tools_size(), 1);
  EXPECT_EQ(frame.tools(0).contacts_size(), 1);
  EXPECT_GT(frame.tools(0).contacts(0).depth_m(), 0);
  EXPECT_FALSE(frame.tools(0).has_force_w_n());
  EXPECT_FALSE(frame.tools(0).has_device_pose());

  watch_context->TryCancel();
  contacts_context->TryCancel();
  poses_viewer->Finish();
  contacts_viewer->Finish();
  device.Finish();
}

// Only streams that need free-body motion get the bodies: a viewer of
// WATCH_PART_BODIES sees the free cube dropped 1 cm come to rest on the
// table (its centre half its side above the table's top); a device whose
// needs lack free_body_motion, and a poses-only viewer, get frames of the
// same scene, whose free-body stage runs, without bodies.
TEST(SessionServiceTest, BodiesGoToStreamsThatNeedThem) {
  TestServer server;
  pb::SceneSpec spec = SmallScene("bodies");
  pb::SceneObject* pebble = spec.add_objects();
  pebble->set_name("pebble");
  pebble->set_kind(pb::OBJECT_KIND_FREE);
  pb::Vector3* size =
      pebble->mutable_model()->mutable_procedural()->mutable_box()->mutable_size_m();
  size->set_x(0.02);
  size->set_y(0.02);
  size->set_z(0.02);
  *pebble->mutable_pose() = PoseAt(0.05, 0.05, 0.03);  // the table's top is at 0.01
  server.Create(spec);
  auto watch_context = ContextWithin(30);
  pb::WatchRequest watch;
  watch.set_scene("bodies");
  watch.add_parts(pb::WATCH_PART_BODIES);
  auto bodies_viewer = server.sessions().Watch(watch_context.get(), watch);
  auto poses_context = ContextWithin(30);
  watch.set_parts(0, pb::WATCH_PART_POSES);
  auto poses_viewer = server.sessions().Watch(poses_context.get(), watch);
  Device device(server, "bodies", "probe", {pb::EFFECT_COLLISION});

  pb::Frame frame;
  ASSERT_TRUE(bodies_viewer->Read(&frame));
  const int64_t first = frame.step();
  while (frame.step() < first + 300 && bodies_viewer->Read(&frame)) {
  }
  ASSERT_EQ(frame.bodies_size(), 1);
  EXPECT_EQ(frame.bodies(0).name(), "pebble");
  EXPECT_NEAR(frame.bodies(0).pose().position_m().z(), 0.02, 1e-4);
  EXPECT_FALSE(frame.bodies(0).held());

  auto moved_bodies = [](const pb::Frame& f) {
    return std::find(f.stages_run().begin(), f.stages_run().end(), pb::EFFECT_FREE_BODY_MOTION) !=
           f.stages_run().end();
  };
  device.Send(1, PoseAt(0, 0, 0.05));
  ASSERT_TRUE(device.ReadUntil(1, frame));
  EXPECT_TRUE(moved_bodies(frame));
  EXPECT_EQ(frame.bodies_size(), 0);
  // The viewer's queue may still hold frames of the steps before the pose:
  // the frame to look at is one that applied it.
  bool read = false;
  for (int n = 0; n < 2000 && (read = poses_viewer->Read(&frame)); ++n) {
    if (frame.tools_size() > 0 && frame.tools(0).last_pose_sequence() >= 1) break;
  }
  ASSERT_TRUE(read);
  ASSERT_GE(frame.tools(0).last_pose_sequence(), 1u);
  EXPECT_TRUE(moved_bodies(frame));
  EXPECT_EQ(frame.bodies_size(), 0);

  watch_context->TryCancel();
  poses_context->TryCancel();
  bodies_viewer->Finish();
  poses_viewer->Finish();
  device.Finish();
}

// Bad session input gets its specific code and leaves the scene as it was:
// unknown scene or tool NOT_FOUND, a NaN or non-unit pose, a NaN or
// negative validity radius or a missing 'open' INVALID_ARGUMENT, an
// unknown watch part INVALID_ARGUMENT.
TEST(SessionServiceTest, BadInputGetsSpecificCodes) {
  TestServer server;
  server.Create(SmallScene("strict"));
  const pb::SceneInfo before = server.Get("strict");

  EXPECT_EQ(Device(server, "nowhere", "probe").Finish().error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(Device(server, "strict", "table").Finish().error_code(), grpc::StatusCode::NOT_FOUND);
  {
    Device device(server, "strict", "probe");
    device.Send(1, PoseAt(0, std::nan(""), 0.05));
    EXPECT_EQ(device.Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  for (double radius : {std::nan(""), -0.01, std::numeric_limits<double>::infinity()}) {
    Device device(server, "strict", "probe");
    device.Send(1, PoseAt(0, 0, 0.05), radius);
    EXPECT_EQ(device.Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT) << radius;
  }
  {
    Device device(server, "strict", "probe");
    pb::Pose pose = PoseAt(0, 0, 0.05);
    pose.mutable_orientation()->set_w(0.5);
    device.Send(1, pose);
    EXPECT_EQ(device.Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  {
    auto context = ContextWithin(10);
    auto stream = server.sessions().Interact(context.get());
    pb::InteractRequest request;
    *request.mutable_pose()->mutable_pose() = PoseAt(0, 0, 0);
    stream->Write(request);
    stream->WritesDone();
    pb::Frame frame;
    while (stream->Read(&frame)) {
    }
    EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  }
  for (const auto& [scene, part] : {std::pair{"nowhere", 1}, std::pair{"strict", 7}}) {
    auto context = ContextWithin(10);
    pb::WatchRequest watch;
    watch.set_scene(scene);
    watch.add_parts(static_cast<pb::WatchPart>(part));
    auto viewer = server.sessions().Watch(context.get(), watch);
    pb::Frame frame;
    while (viewer->Read(&frame)) {
    }
    EXPECT_EQ(viewer->Finish().error_code(), std::string(scene) == "nowhere"
                                                 ? grpc::StatusCode::NOT_FOUND
                                                 : grpc::StatusCode::INVALID_ARGUMENT);
  }
  const pb::SceneInfo after = server.Get("strict");
  EXPECT_TRUE(MessageDifferencer::Equals(before.spec(), after.spec()));
  EXPECT_EQ(before.revision(), after.revision());
}

}  // namespace
}  // namespace hs::testing
