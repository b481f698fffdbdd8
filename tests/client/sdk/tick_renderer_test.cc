#include "client/sdk/tick_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>

// Counts the allocations and frees made while `counting` is set, on any
// thread.
namespace {
std::atomic<bool> counting{false};
std::atomic<int64_t> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  if (counting) ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  if (counting && p != nullptr) ++allocations;
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  if (counting && p != nullptr) ++allocations;
  std::free(p);
}

namespace hs::sdk {
namespace {

// The floor z = 0 of 400 N/m under a proxy resting on it at the origin;
// `planes` copies of it (as corners and fine meshes give several).
LocalModel Floor(int planes = 1) {
  LocalModel model;
  model.validity_radius_m = 0.01;
  model.force_clamp_n = 10;
  ConstraintPlane plane;
  plane.stiffness_n_per_m = 400;
  plane.damping_ns_per_m = 0.5;
  model.planes.assign(planes, plane);
  return model;
}

haptics::Pose At(double z) {
  haptics::Pose pose;
  pose.position_m[2] = z;
  return pose;
}

Feed Connected(uint64_t stream) {
  Feed feed;
  feed.stream = stream;
  feed.connected = true;
  return feed;
}

void WithModel(Feed& feed, const LocalModel& model) {
  feed.model = model;
  feed.model_stream = feed.stream;
  ++feed.model_serial;
}

TEST(TickRendererTest, NothingIsFeltWithoutALinkOrAModel) {
  // Down: zero force, no flag. Up without a model yet: zero, kConnected.
  TickRenderer renderer(haptics::DeviceOptions{});
  haptics::TickOutput out = renderer.Tick(At(-0.005), Feed{});
  EXPECT_EQ(out.flags, 0u);
  EXPECT_EQ(out.force_n[2], 0);
  out = renderer.Tick(At(-0.005), Connected(1));
  EXPECT_EQ(out.flags, haptics::kConnected);
  EXPECT_EQ(out.force_n[2], 0);
}

TEST(TickRendererTest, RendersTheModelAsAFreshHapticLoop) {
  // Pressing into the floor: each tick's force and torque are those of a
  // HapticLoop of its own given the same model and poses.
  TickRenderer renderer(haptics::DeviceOptions{});
  HapticLoop oracle(HapticLoopOptions{.tick_s = 1e-3});
  Feed feed = Connected(1);
  WithModel(feed, Floor());
  oracle.SetModel(feed.model);
  for (int k = 0; k < 50; ++k) {
    const haptics::Pose pose = At(-1e-4 * k);
    const haptics::TickOutput out = renderer.Tick(pose, feed);
    Isometry3d X_WD = Isometry3d::Identity();
    X_WD.translation().z() = pose.position_m[2];
    const HapticOutput expected = oracle.Tick(X_WD);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(out.force_n[i], expected.force_W[i]) << "tick " << k;
      EXPECT_EQ(out.torque_nm[i], expected.torque_W[i]) << "tick " << k;
    }
    EXPECT_EQ((out.flags & haptics::kTouching) != 0, expected.touching);
  }
  // 4.9 mm in: 400 N/m's spring, up.
  EXPECT_NEAR(renderer.Tick(At(-0.0049), feed).force_n[2], 400 * 0.0049, 0.05);
}

TEST(TickRendererTest, BadPoseHoldsTheLastForce) {
  // NaN, infinite or non-unit: kInvalidPose, the last force, counted.
  TickRenderer renderer(haptics::DeviceOptions{});
  Feed feed = Connected(1);
  WithModel(feed, Floor());
  haptics::TickOutput last;
  for (int k = 0; k < 20; ++k) last = renderer.Tick(At(-2e-4 * k), feed);
  ASSERT_GT(last.force_n[2], 1);
  haptics::Pose nan = At(-0.004);
  nan.position_m[0] = NAN;
  haptics::Pose long_quaternion = At(-0.004);
  long_quaternion.orientation_wxyz[1] = 0.01;
  haptics::Pose infinite = At(-0.004);
  infinite.orientation_wxyz[0] = INFINITY;
  for (const haptics::Pose& bad : {nan, long_quaternion, infinite}) {
    const haptics::TickOutput out = renderer.Tick(bad, feed);
    EXPECT_EQ(out.status, haptics::TickStatus::kInvalidPose);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(out.force_n[i], last.force_n[i]);
  }
  EXPECT_EQ(renderer.counts().rejected_poses, 3);
  EXPECT_FALSE(TickRenderer::ValidPose(long_quaternion));
  haptics::Pose turned = At(0);
  turned.orientation_wxyz[0] = std::sqrt(0.5);
  turned.orientation_wxyz[3] = std::sqrt(0.5);
  EXPECT_TRUE(TickRenderer::ValidPose(turned));
}

TEST(TickRendererTest, ANewStreamStartsAFreshLoop) {
  // After a reconnection the old stream's model is not rendered; the new
  // stream's first model renders as a loop that never ticked.
  TickRenderer renderer(haptics::DeviceOptions{});
  Feed feed = Connected(1);
  WithModel(feed, Floor());
  for (int k = 0; k < 20; ++k) renderer.Tick(At(-2e-4 * k), feed);
  feed.stream = 2;
  haptics::TickOutput out = renderer.Tick(At(-0.004), feed);
  EXPECT_EQ(out.flags, haptics::kConnected);
  EXPECT_EQ(out.force_n[2], 0);
  WithModel(feed, Floor());
  out = renderer.Tick(At(-0.004), feed);
  HapticLoop oracle(HapticLoopOptions{.tick_s = 1e-3});
  oracle.SetModel(feed.model);
  Isometry3d X_WD = Isometry3d::Identity();
  X_WD.translation().z() = -0.004;
  EXPECT_EQ(out.force_n[2], oracle.Tick(X_WD).force_W.z());
}

TEST(TickRendererTest, CountsSpanStreams) {
  // A model that fails the checks is counted; the count stays when a new
  // stream starts a fresh loop, and the passivity controller's work adds
  // up over both.
  TickRenderer renderer(haptics::DeviceOptions{});
  Feed feed = Connected(1);
  LocalModel bad = Floor();
  bad.validity_radius_m = NAN;
  WithModel(feed, bad);
  renderer.Tick(At(0), feed);
  EXPECT_EQ(renderer.counts().models_rejected, 1);
  feed.stream = 2;
  WithModel(feed, Floor());
  renderer.Tick(At(0), feed);
  EXPECT_EQ(renderer.counts().models_rejected, 1);
  WithModel(feed, bad);
  renderer.Tick(At(0), feed);
  EXPECT_EQ(renderer.counts().models_rejected, 2);
}

TEST(TickRendererTest, WithoutTheLocalModelTheFramesForceIsApplied) {
  // DeviceOptions::local_model false: the newest frame's force as it is,
  // while connected; a model in the feed is not rendered; zero when down.
  TickRenderer renderer(haptics::DeviceOptions{.local_model = false});
  Feed feed = Connected(1);
  feed.force_n[0] = 0.5;
  feed.force_n[2] = 1.25;
  WithModel(feed, Floor());
  haptics::TickOutput out = renderer.Tick(At(-0.004), feed);
  EXPECT_EQ(out.flags, haptics::kConnected);
  EXPECT_EQ(out.force_n[0], 0.5);
  EXPECT_EQ(out.force_n[1], 0);
  EXPECT_EQ(out.force_n[2], 1.25);
  EXPECT_EQ(out.torque_nm[0], 0);
  feed.connected = false;
  out = renderer.Tick(At(-0.004), feed);
  EXPECT_EQ(out.flags, 0u);
  EXPECT_EQ(out.force_n[2], 0);
}

TEST(TickRendererTest, BeyondValidityIsFlaggedAndCounted) {
  // Past the validity radius (1 cm from the floor's proxy at the origin):
  // kBeyondValidity, counted.
  TickRenderer renderer(haptics::DeviceOptions{});
  Feed feed = Connected(1);
  WithModel(feed, Floor());
  int64_t beyond = 0;
  for (double x : {0.0, 0.005, 0.0099, 0.0101, 0.02, 0.011, 0.003, 0.05}) {
    haptics::Pose pose = At(0.001);
    pose.position_m[0] = x;
    const haptics::TickOutput out = renderer.Tick(pose, feed);
    const double distance = std::hypot(x, 0.001);
    EXPECT_EQ((out.flags & haptics::kBeyondValidity) != 0, distance > 0.01) << "x = " << x;
    if (distance > 0.01) ++beyond;
  }
  EXPECT_EQ(beyond, 4);
  EXPECT_EQ(renderer.beyond_validity_ticks(), beyond);
}

// The floor's model with a surface of `faces` triangles of it (a strip
// under the origin, each with its own material up to the cap) and a cube
// tool, or that surface named alone.
LocalModel FloorSurface(int faces, uint64_t revision, bool body = true) {
  LocalModel model = Floor(1);
  auto s = std::make_shared<ModelSurface>();
  s->revision = revision;
  s->radius_m = 0.01;
  if (body) {
    for (int i = 0; i < 8; ++i) {
      s->tool_vertices_T.emplace_back(i & 1 ? 0.01 : -0.01, i & 2 ? 0.01 : -0.01,
                                      i & 4 ? 0.02 : 0.0);
    }
    s->tool_triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                         {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    for (int i = 0; i <= faces; ++i) {
      s->vertices_W.emplace_back(-0.1 + 0.2 * i / faces, -0.1, 0);
      s->vertices_W.emplace_back(-0.1 + 0.2 * i / faces, 0.1, 0);
    }
    for (int i = 0; i < faces; ++i) {
      s->triangles.push_back(i % 2 == 0 ? std::array<int32_t, 3>{i, i + 2, i + 1}
                                        : std::array<int32_t, 3>{i, i + 1, i + 2});
      s->triangle_materials.push_back(std::min(i, kMaxSurfaceMaterials - 1));
      if (i < kMaxSurfaceMaterials) s->materials.push_back({.stiffness_n_per_m = 400});
    }
  }
  model.surface = std::move(s);
  return model;
}

TEST(TickRendererTest, TicksAllocateNothing) {
  // Ticks taking new models of up to 16 planes, surfaces of up to the most
  // faces and materials and models naming them alone, a new stream, a
  // link down and bad poses allocate and free nothing once the renderer is
  // built (the feeds hold the surfaces, as the network thread does).
  TickRenderer renderer(haptics::DeviceOptions{});
  Feed feed = Connected(1);
  std::vector<Feed> feeds;
  for (int planes = 0; planes <= 16; ++planes) {
    WithModel(feed, Floor(planes));
    feeds.push_back(feed);
  }
  for (const int faces : {12, 600, kMaxSurfaceTriangles}) {
    WithModel(feed, FloorSurface(faces, faces));
    feeds.push_back(feed);
    WithModel(feed, FloorSurface(faces, faces, false));
    feeds.push_back(feed);
  }
  Feed reconnected = feed;
  reconnected.stream = 2;
  WithModel(reconnected, Floor(16));
  haptics::Pose nan = At(0);
  nan.position_m[2] = NAN;
  counting = true;
  for (int k = 0; k < 1000; ++k) {
    renderer.Tick(At(-1e-5 * (k % 100)), feeds[k % feeds.size()]);
  }
  renderer.Tick(nan, feed);
  renderer.Tick(At(0), Feed{});
  for (int k = 0; k < 10; ++k) renderer.Tick(At(-0.001), reconnected);
  counting = false;
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace hs::sdk
