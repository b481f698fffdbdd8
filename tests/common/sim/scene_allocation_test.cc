// Scene::Step allocates nothing in steady state where it owns the work.
// A binary of its own: it links the counting global operator new.

#include <gtest/gtest.h>

#include <vector>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/allocation_counter.h"
#include "tests/common/sim/at_pose.h"

namespace hs {
namespace {

// Keeps the counter's own check from being optimized away.
volatile const void* sink = nullptr;

// After warm-up, steps that move a tool (with every effect on, sub-steps
// and the broad phase) and free bodies in free fall allocate nothing:
// frames, candidate lists and scratch are reused. No pair comes within
// the boxes' reach here: the steps with contacts are step_bench's and
// tests/server/step_allocation_test.cc's.
TEST(SceneAllocationTest, SteadyStateStepAllocatesNothing) {
  {
    // The counter sees allocations: the test cannot pass for want of it.
    const long before = AllocationCount();
    std::vector<int> probe_vector(10);
    sink = probe_vector.data();
    EXPECT_EQ(AllocationCount() - before, 1);
  }
  for (const bool continuous : {true, false}) {
    SCOPED_TRACE(continuous);
    SceneOptions options;
    if (!continuous) options.enabled = EffectSet::All().Without(Effect::kContinuousCollision);
    std::unique_ptr<Scene> scene = *Scene::Create(options);
    for (int i = 0; i < 10; ++i) {
      ASSERT_TRUE(scene
                      ->AddObject(*HapticObject::Create("post", MakeBox(Vector3d(0.01, 0.01, 0.2))),
                                  ObjectKind::kFixed, At(0.1 * i, 0.5, 0))
                      .ok());
    }
    ASSERT_TRUE(scene
                    ->AddObject(*HapticObject::Create("ball", MakeIcosphere(0.01, 2)),
                                ObjectKind::kFree, At(0, -0.5, 100))
                    .ok());
    const ObjectId probe =
        *scene->AddObject(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))),
                          ObjectKind::kTool, At(0, 0, 0));
    auto step = [&](int i) {
      // Alternating 1 mm and 5 cm moves: plain steps and sub-stepped ones.
      const double x = 0.001 * i + (i % 2 ? 0.05 : 0.0);
      EXPECT_TRUE(scene->SetDevicePose(probe, At(x, 0, 0)).ok());
      const StepFrame& frame = scene->Step();
      EXPECT_EQ(frame.tools[0].contacts.size(), 0u);
      return frame.tools[0].substeps;
    };
    for (int i = 0; i < 10; ++i) step(i);
    const long before = AllocationCount();
    int substeps = 0;
    for (int i = 10; i < 200; ++i) substeps += step(i);
    EXPECT_EQ(AllocationCount() - before, 0);
    if (!continuous) {
      EXPECT_GT(substeps, 190);  // the long moves were split
    }
  }
}

}  // namespace
}  // namespace hs
