// Scene::Step allocates nothing in steady state where it owns the work.
// A binary of its own: it replaces the global operator new to count.

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"

namespace {
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, std::align_val_t align) {
  ++allocations;
  const auto a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) { return operator new(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace hs {
namespace {

// After warm-up, steps that move a tool (with every effect on, sub-steps
// and the broad phase) and free bodies in free fall allocate nothing:
// frames, candidate lists and scratch are reused. No pair comes within
// the boxes' reach here, so no contact query of common/contact (whose
// results still allocate, see docs/simulation.md) runs.
TEST(SceneAllocationTest, SteadyStateStepAllocatesNothing) {
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
    const long before = allocations.load();
    int substeps = 0;
    for (int i = 10; i < 200; ++i) substeps += step(i);
    EXPECT_EQ(allocations.load() - before, 0);
    if (!continuous) {
      EXPECT_GT(substeps, 190);  // the long moves were split
    }
  }
}

}  // namespace
}  // namespace hs
