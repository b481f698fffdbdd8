#include "server/frame_message.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace hs {
namespace {

// Two streams' identities (FillFrameMessage only compares them).
struct NoSink : FrameSink {
  void Offer(std::shared_ptr<const StepSnapshot>) override {}
  void Close(const absl::Status&) override {}
};

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

// Each local model revision goes to a stream once: a device stream gets its
// own tool's model only, a viewer every tool's; a newer revision goes out
// again, and so does every model of a new scene (new names table).
TEST(FrameMessageTest, EachModelRevisionGoesOutOnce) {
  NoSink device, viewer;
  auto names = std::make_shared<const std::vector<std::string>>(
      std::vector<std::string>{"floor", "probe", "stylus"});
  ModelsSent device_sent{.own_tool_only = true}, viewer_sent;
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
            (std::vector<uint64_t>{1, 0}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 1, names), &viewer, viewer_sent),
            (std::vector<uint64_t>{1, 1}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 1, names), &device, device_sent),
            (std::vector<uint64_t>{0, 0}));
  EXPECT_EQ(models(*Snapshot(&device, 1, 2, names), &viewer, viewer_sent),
            (std::vector<uint64_t>{0, 2}));
  EXPECT_EQ(models(*Snapshot(&device, 2, 2, names), &device, device_sent),
            (std::vector<uint64_t>{2, 0}));
  FrameParts no_models;
  no_models.local_model = false;
  FillFrameMessage(*Snapshot(&device, 3, 3, names), no_models, &device, 0, 0, device_sent, frame);
  EXPECT_FALSE(frame.tools(0).has_local_model());
  auto rebuilt = std::make_shared<const std::vector<std::string>>(*names);
  EXPECT_EQ(models(*Snapshot(&device, 2, 2, rebuilt), &device, device_sent),
            (std::vector<uint64_t>{2, 0}));
}

}  // namespace
}  // namespace hs
