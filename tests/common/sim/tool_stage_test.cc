// The tool stage (tool_stage.h) through the scene's door: the halves of
// every tool stepped on several threads give what one thread gives.
#include "common/sim/tool_stage.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/same_tool_frame.h"

namespace hs {
namespace {

constexpr int kTools = 5;

// A floor with a torus "organ" lying on it and kTools 2 cm cube probes
// spread around the organ's crest, with every effect on.
std::unique_ptr<Scene> MakeScene(int threads) {
  std::unique_ptr<Scene> scene = *Scene::Create({});
  EXPECT_TRUE(scene->SetThreads(threads).ok());
  (void)*scene->AddObject(*HapticObject::Create("floor", MakeBox(Vector3d(1, 1, 0.05))),
                          ObjectKind::kFixed, At(0, 0, -0.025));
  (void)*scene->AddObject(*HapticObject::Create("organ", MakeTorus(0.1, 0.04, 48, 24)),
                          ObjectKind::kFixed, At(0, 0, 0.04));
  for (int i = 0; i < kTools; ++i) {
    (void)*scene->AddObject(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))),
                            ObjectKind::kTool, At(0.1, 0.02 * i, 0.1));
  }
  return scene;
}

// Tool i presses 1 mm a step onto the crest (top at z = 0.08, the probe's
// bottom 1 cm under its centre) until 6 mm in, then slides along x, each
// tool at its own speed so that they do different work in one step.
Isometry3d DevicePose(int tool, int step) {
  const double z = std::max(0.1 - 0.001 * step, 0.084);
  const double x = 0.1 - (step > 16 ? 0.0004 * (tool + 1) * (step - 16) : 0.0);
  return At(x, 0.02 * tool, z);
}

// Stepping the tools on several threads gives bit-identical frames and the
// same stage counts as stepping them one after the other.
TEST(ToolStageTest, ThreadsGiveIdenticalFrames) {
  for (const int threads : {2, 3}) {
    std::unique_ptr<Scene> serial = MakeScene(1);
    std::unique_ptr<Scene> parallel = MakeScene(threads);
    int touching_steps = 0;
    for (int step = 1; step <= 40; ++step) {
      for (int tool = 0; tool < kTools; ++tool) {
        const ObjectId id = 2 + tool;
        ASSERT_TRUE(serial->SetDevicePose(id, DevicePose(tool, step)).ok());
        ASSERT_TRUE(parallel->SetDevicePose(id, DevicePose(tool, step)).ok());
      }
      const StepFrame a = serial->Step();
      const StepFrame& b = parallel->Step();
      ExpectSameToolFrames(a, b);
      for (const ToolFrame& tool : a.tools) touching_steps += tool.force_W.norm() > 0;
    }
    // The test means something only if the tools did touch the organ.
    EXPECT_GT(touching_steps, kTools * 10);
    for (int e = 0; e < kNumEffects; ++e) {
      EXPECT_EQ(serial->stats()[e].runs, parallel->stats()[e].runs) << e;
    }
  }
}

// Stepped directly: a device moved 1.5 cm into a floor leaves its proxy
// on the floor (the probe's bottom at z = 0 within the tolerance), which
// is what free bodies meet (ProxyMotionOf: the pose and the move from the
// start); a step clears "moved", a new pose sets it again.
TEST(ToolStageTest, ProxyStopsOnTheFloorAndReportsItsMove) {
  SceneObjects objects;
  HapticObject floor = *HapticObject::Create("floor", MakeBox(Vector3d(1, 1, 0.1)));
  CollisionModel floor_model(floor, BvType::kObbRss, 1e-7);
  objects.Add(std::move(floor), std::move(floor_model), ObjectKind::kFixed, At(0, 0, -0.05));
  HapticObject probe = *HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02)));
  CollisionModel probe_model(probe, BvType::kObbRss, 1e-7);
  const ObjectId id =
      objects.Add(std::move(probe), std::move(probe_model), ObjectKind::kTool, At(0, 0, 0.02));
  const SceneOptions options;
  ToolStage stage(options, objects);
  stage.Add(id, At(0, 0, 0.02));
  WorkerPool workers(1);
  std::vector<ToolFrame> frames;
  StageStatsTable stats{};
  stage.Step(EffectSet::All(), workers, frames, stats);
  EXPECT_FALSE(stage.AnyMoved());
  stage.SetDevicePose(id, At(0, 0, 0.005));
  EXPECT_TRUE(stage.AnyMoved());
  stage.Step(EffectSet::All(), workers, frames, stats);
  EXPECT_FALSE(stage.AnyMoved());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].tool, id);
  const ToolStage::ProxyMotion proxy = stage.ProxyMotionOf(id);
  EXPECT_NEAR(proxy.X_WP.translation().z(), 0.01, 1e-6);
  EXPECT_TRUE(proxy.X_WP.isApprox(frames[0].X_WP));
  EXPECT_NEAR(proxy.motion_W.z(), 0.01 - 0.02, 1e-6);
  EXPECT_GT(frames[0].force_W.z(), 0);
  EXPECT_EQ(stats[static_cast<int>(Effect::kReversingVector)].runs, 2);
}

// The thread count is checked: 0 and 65 are refused, and the scene keeps
// stepping on what it had.
TEST(ToolStageTest, RejectsThreadCountOutOfRange) {
  std::unique_ptr<Scene> scene = MakeScene(2);
  EXPECT_EQ(scene->SetThreads(0).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(scene->SetThreads(65).code(), absl::StatusCode::kInvalidArgument);
  ASSERT_TRUE(scene->SetDevicePose(2, DevicePose(0, 20)).ok());
  EXPECT_EQ(scene->Step().tools.size(), static_cast<size_t>(kTools));
}

}  // namespace
}  // namespace hs
