// The tool stage (tool_stage.h) through the scene's door: the halves of
// every tool stepped on several threads give what one thread gives.
#include "common/sim/tool_stage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/same_tool_frame.h"

namespace hs {
namespace {

constexpr int kTools = 5;

// A floor with a torus "organ" lying on it and `tools` 2 cm cube probes
// spread around the organ's crest, with every effect on. Every step with
// more than one job runs on the threads, however short.
std::unique_ptr<Scene> MakeScene(int threads, int tools = kTools) {
  std::unique_ptr<Scene> scene = *Scene::Create({.parallel_work_share = 0});
  EXPECT_TRUE(scene->SetThreads(threads).ok());
  (void)*scene->AddObject(*HapticObject::Create("floor", MakeBox(Vector3d(1, 1, 0.05))),
                          ObjectKind::kFixed, At(0, 0, -0.025));
  (void)*scene->AddObject(*HapticObject::Create("organ", MakeTorus(0.1, 0.04, 48, 24)),
                          ObjectKind::kFixed, At(0, 0, 0.04));
  for (int i = 0; i < tools; ++i) {
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
// is what free bodies meet (ProxyMotionOf: the pose and the move over the
// last step); a step clears "moved", a new pose sets it again, and a
// proxy that moved steps once more to show it rests.
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
  EXPECT_TRUE(stage.NothingToStep());
  stage.SetDevicePose(id, At(0, 0, 0.005));
  EXPECT_FALSE(stage.NothingToStep());
  stage.Step(EffectSet::All(), workers, frames, stats);
  // The proxy moved: one more step shows whether it rests.
  EXPECT_FALSE(stage.NothingToStep());
  stage.Step(EffectSet::All(), workers, frames, stats);
  EXPECT_TRUE(stage.NothingToStep());
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].tool, id);
  const ToolStage::ProxyMotion proxy = stage.ProxyMotionOf(id);
  EXPECT_NEAR(proxy.X_WP.translation().z(), 0.01, 1e-6);
  EXPECT_TRUE(proxy.X_WP.isApprox(frames[0].X_WP));
  EXPECT_NEAR(proxy.motion_W.z(), 0, 1e-12) << "at rest";
  EXPECT_GT(frames[0].force_W.z(), 0);
  EXPECT_EQ(stats[static_cast<int>(Effect::kReversingVector)].runs, 3);

  // A device asking for a fresh model makes a step.
  stage.RequestLocalModel(id);
  EXPECT_FALSE(stage.NothingToStep());
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

namespace hs {
namespace {

// One probe (id 2) over the organ's crest, a remote device's needs on.
std::unique_ptr<Scene> RemoteDeviceScene() {
  std::unique_ptr<Scene> scene = MakeScene(1, 1);
  scene->SetNeeded(EffectSet{Effect::kForce, Effect::kFriction, Effect::kLocalModel});
  return scene;
}

// Points of the organ's faces in the world (its vertices, its faces'
// centroids and edges' midpoints), as MakeScene places it.
const std::vector<Vector3d>& OrganSamples() {
  static const std::vector<Vector3d> samples = [] {
    const MeshInput organ = MakeTorus(0.1, 0.04, 48, 24);
    const Vector3d offset(0, 0, 0.04);
    std::vector<Vector3d> out;
    for (const Vector3d& p : organ.positions) out.push_back(p + offset);
    for (const FaceInput& face : organ.faces) {
      const Vector3d& a = organ.positions[face.vertices[0]];
      const Vector3d& b = organ.positions[face.vertices[1]];
      const Vector3d& c = organ.positions[face.vertices[2]];
      out.push_back((a + b + c) / 3 + offset);
      out.push_back((a + b) / 2 + offset);
      out.push_back((b + c) / 2 + offset);
      out.push_back((c + a) / 2 + offset);
    }
    return out;
  }();
  return samples;
}

// Checks by brute force that an anchored `model` holds the organ out: every
// point of its faces within the model's radius of the tool (a 2 cm cube at
// the model's proxy) lies behind one of its planes, read as a device's loop
// reads them (its gap in front of its tool point); when `built`, the
// model it was anchored from, was cut at its most planes, only within its
// farthest plane's gap less the `slide` (the nearest faces are the ones
// kept). Returns how many points it checked.
int CheckHoldsOrganOut(const LocalModel& model, const LocalModel& built, const Vector3d& slide,
                       int step) {
  double holds_m = model.validity_radius_m;
  if (built.planes.size() == 16) {
    holds_m = std::min(holds_m, built.planes.back().gap_m - slide.norm());
  }
  const AlignedBox3d tool(model.X_WP.translation() - Vector3d::Constant(0.01),
                          model.X_WP.translation() + Vector3d::Constant(0.01));
  int checked = 0;
  for (const Vector3d& p_W : OrganSamples()) {
    if (tool.exteriorDistance(p_W) > holds_m) continue;
    ++checked;
    EXPECT_TRUE(std::any_of(model.planes.begin(), model.planes.end(),
                            [&](const ConstraintPlane& plane) {
                              return plane.gap_m + plane.normal_W.dot(p_W - plane.tool_point_W) <=
                                     1e-9;
                            }))
        << "step " << step << " point " << p_W.transpose();
  }
  return checked;
}

// A tool gets a new model only when the last one no longer serves
// (docs/simulation.md, Local models only when needed), and each new one is
// either the model a fresh search makes there, or, for a touching proxy
// that slid a little, the last such model anchored where the proxy is now
// (common/sim/local_model_anchor.h). The oracles: the same poses in a scene
// asked for a fresh search every step give the same model, plane for
// plane, at each revision built (the pairs of the last search serve while
// the proxy stays within their margin, common/sim/local_model_builder.h);
// an anchored one holds the half-spaces of the last one built, by hand
// (each gap grows by its normal times the slide), within the radius less
// the slide, and the proxy rests on one of them. Between revisions the
// proxy stays within a tenth of the 1 cm radius of the model's and,
// touching, where it was.
// A model built from kept pairs against one searched afresh at the same
// step: plane for plane, bit for bit.
void ExpectSamePlanes(const LocalModel& model, const LocalModel& searched, int step) {
  EXPECT_EQ(model.validity_radius_m, searched.validity_radius_m) << step;
  ASSERT_EQ(model.planes.size(), searched.planes.size()) << step;
  for (size_t i = 0; i < model.planes.size(); ++i) {
    EXPECT_EQ(model.planes[i].normal_W, searched.planes[i].normal_W) << step;
    EXPECT_EQ(model.planes[i].gap_m, searched.planes[i].gap_m) << step;
    EXPECT_EQ(model.planes[i].tool_point_W, searched.planes[i].tool_point_W) << step;
    EXPECT_EQ(model.planes[i].separating, searched.planes[i].separating) << step;
  }
}

TEST(ToolStageTest, EachStepsModelIsTheSearchedOne) {
  constexpr double kRadius = 0.01;
  std::unique_ptr<Scene> kept = RemoteDeviceScene();
  std::unique_ptr<Scene> searched = RemoteDeviceScene();
  int pressing = 0;
  int held = 0;
  int anchored = 0;
  int built = 0;
  int brute_forced = 0;
  long separating = 0;
  uint64_t last_revision = 0;
  LocalModel last_built;
  Vector3d last_proxy = Vector3d::Constant(1);
  // Down onto the crest and 5 mm into it, then 15 mm along it, then still.
  for (int step = 0; step < 70; ++step) {
    const int s = std::min(step, 60);
    const double z = 0.095 - 0.0005 * std::min(s, 30);
    const double x = 0.1 - (s > 30 ? 0.0005 * (s - 30) : 0.0);
    ASSERT_TRUE(kept->SetDevicePose(2, At(x, 0, z)).ok());
    ASSERT_TRUE(searched->SetDevicePose(2, At(x, 0, z)).ok());
    ASSERT_TRUE(searched->RequestLocalModel(2).ok());
    const ToolFrame& a = kept->Step().tools[0];
    const ToolFrame& b = searched->Step().tools[0];
    const LocalModel& model = a.local_model;
    ASSERT_NE(model.revision, 0u);
    const bool pressing_on = step <= 60;  // then the device holds still
    const bool new_model = model.revision != last_revision;
    if (step > 64) {
      EXPECT_FALSE(new_model) << "a still device, step " << step;
    }
    last_revision = model.revision;
    if (!pressing_on) continue;
    pressing += (a.X_WP.translation() - last_proxy).norm() < 1e-7;
    last_proxy = a.X_WP.translation();
    if (!new_model) {
      ++held;
      const double moved = (a.X_WP.translation() - model.X_WP.translation()).norm();
      EXPECT_LE(moved, 0.1 * model.validity_radius_m) << step;
      if (model.touching) {
        EXPECT_EQ(moved, 0) << step;
      }
      continue;
    }
    EXPECT_TRUE(model.X_WP.isApprox(b.local_model.X_WP, 0.0)) << step;
    EXPECT_EQ(model.p_WD, b.local_model.p_WD) << step;
    EXPECT_EQ(model.touching, b.local_model.touching) << step;
    if (model.validity_radius_m < kRadius) {  // anchored
      ++anchored;
      ASSERT_TRUE(model.touching) << step;
      const Vector3d slide = model.X_WP.translation() - last_built.X_WP.translation();
      EXPECT_LE(slide.norm(), 0.25 * kRadius) << step;
      EXPECT_DOUBLE_EQ(model.validity_radius_m, kRadius - slide.norm()) << step;
      double nearest = std::numeric_limits<double>::infinity();
      for (const ConstraintPlane& plane : model.planes) {
        // The same plane (parallel ones differ in their gaps).
        EXPECT_TRUE(std::any_of(last_built.planes.begin(), last_built.planes.end(),
                                [&](const ConstraintPlane& p) {
                                  return p.normal_W == plane.normal_W &&
                                         p.separating == plane.separating &&
                                         std::abs(std::max(p.gap_m + p.normal_W.dot(slide), 0.0) -
                                                  plane.gap_m) <= 1e-15;
                                }))
            << step;
        nearest = std::min(nearest, plane.gap_m);
      }
      EXPECT_LE(nearest, 1e-7) << "the proxy rests on a plane, step " << step;
      brute_forced += CheckHoldsOrganOut(model, last_built, slide, step);
      continue;
    }
    ++built;
    last_built = model;
    ExpectSamePlanes(model, b.local_model, step);
    separating += std::count_if(model.planes.begin(), model.planes.end(),
                                [](const ConstraintPlane& p) { return p.separating; });
  }
  EXPECT_GT(separating, 0) << "the crest's planes must separate (separating_planes.h)";
  EXPECT_GT(held, 5) << "the path must hold models between revisions";
  EXPECT_GT(pressing, 5) << "the path must press with the proxy held";
  EXPECT_GT(anchored, 5) << "the slide must anchor models";
  EXPECT_GT(built, 3) << "the slide must build models";
  EXPECT_GT(brute_forced, 20) << "the anchored models must be checked by brute force";
  EXPECT_EQ(kept->RequestLocalModel(0).code(), absl::StatusCode::kFailedPrecondition);
}

// Along the press and slide over the crest, every model carries a surface
// (the probe is convex), the proxy within kSurfaceMoveFraction of the
// radius of its centre; models share one surface (the same object) until
// the proxy moves past that, and each new surface comes with a new model.
TEST(ToolStageTest, ModelsShareASurfaceUntilTheProxyMovesOn) {
  constexpr double kRadius = 0.01;
  std::unique_ptr<Scene> scene = RemoteDeviceScene();
  std::shared_ptr<const ModelSurface> last;
  uint64_t last_revision = 0;
  int surfaces = 0;
  for (int step = 0; step < 70; ++step) {
    const int s = std::min(step, 60);
    const double z = 0.095 - 0.0005 * std::min(s, 30);
    const double x = 0.1 - (s > 30 ? 0.0005 * (s - 30) : 0.0);
    ASSERT_TRUE(scene->SetDevicePose(2, At(x, 0, z)).ok());
    const ToolFrame& frame = scene->Step().tools[0];
    const LocalModel& model = frame.local_model;
    ASSERT_TRUE(model.surface) << step;
    const ModelSurface& surface = *model.surface;
    EXPECT_EQ(surface.radius_m, kSurfaceReachFraction * kRadius);
    EXPECT_LE((frame.X_WP.translation() - surface.center_W).norm(), kSurfaceMoveFraction * kRadius)
        << step;
    EXPECT_GT(surface.triangles.size(), 0u);
    if (model.surface != last) {
      ++surfaces;
      EXPECT_EQ(surface.revision, last ? last->revision + 1 : 1u) << step;
      EXPECT_NE(model.revision, last_revision) << "a new surface, a new model, step " << step;
    } else {
      EXPECT_EQ(surface.revision, last->revision);
    }
    last = model.surface;
    last_revision = model.revision;
  }
  EXPECT_GE(surfaces, 3) << "the 15 mm slide must move past two surfaces";
}

// A device that reads the surface alone: along the press and slide, every
// model carries the surface of a device that reads planes too, no planes,
// and the same proxy state (where it is, whether and where it touches: the
// torque's lever); a touching proxy that slid gets a new model each step,
// as an anchored one. Back to planes, the next model has the planes a
// fresh search makes. Not a tool: NOT_FOUND.
TEST(ToolStageTest, ADeviceThatReadsTheSurfaceAloneGetsNoPlanes) {
  std::unique_ptr<Scene> alone = RemoteDeviceScene();
  std::unique_ptr<Scene> planes = RemoteDeviceScene();
  ASSERT_TRUE(alone->SetSurfaceOnly(2, true).ok());
  EXPECT_EQ(alone->SetSurfaceOnly(99, true).code(), absl::StatusCode::kNotFound);
  uint64_t last_revision = 0;
  Isometry3d last_X_WP = Isometry3d::Identity();
  int touching = 0;
  for (int step = 0; step < 60; ++step) {
    const double z = 0.095 - 0.0005 * std::min(step, 30);
    const double x = 0.1 - (step > 30 ? 0.0005 * (step - 30) : 0.0);
    ASSERT_TRUE(alone->SetDevicePose(2, At(x, 0, z)).ok());
    ASSERT_TRUE(planes->SetDevicePose(2, At(x, 0, z)).ok());
    const LocalModel& model = alone->Step().tools[0].local_model;
    const LocalModel& both = planes->Step().tools[0].local_model;
    ASSERT_TRUE(model.surface && both.surface) << step;
    EXPECT_TRUE(model.planes.empty()) << step;
    EXPECT_EQ(model.surface->vertices_W, both.surface->vertices_W) << step;
    EXPECT_EQ(model.surface->triangles, both.surface->triangles) << step;
    EXPECT_EQ(model.touching, both.touching) << step;
    EXPECT_TRUE(model.X_WP.isApprox(both.X_WP, 0.0)) << step;
    // The whole radius: an anchored model of planes loses its slide.
    EXPECT_EQ(model.validity_radius_m, 0.01) << step;
    EXPECT_LE(both.validity_radius_m, model.validity_radius_m) << step;
    if (model.touching) {
      ++touching;
      EXPECT_EQ(model.touch_point_W, both.touch_point_W) << step;
      if (!model.X_WP.isApprox(last_X_WP, 0.0)) {
        EXPECT_GT(model.revision, last_revision) << "a touching proxy slid, step " << step;
      }
    }
    last_revision = model.revision;
    last_X_WP = model.X_WP;
  }
  EXPECT_GT(touching, 20);
  ASSERT_TRUE(alone->SetSurfaceOnly(2, false).ok());
  ASSERT_TRUE(alone->SetDevicePose(2, At(0.085, 0, 0.08)).ok());
  ASSERT_TRUE(planes->SetDevicePose(2, At(0.085, 0, 0.08)).ok());
  ASSERT_TRUE(planes->RequestLocalModel(2).ok());
  const LocalModel& model = alone->Step().tools[0].local_model;
  const LocalModel& fresh = planes->Step().tools[0].local_model;
  EXPECT_GT(model.revision, last_revision);
  EXPECT_FALSE(model.planes.empty());
  ExpectSamePlanes(model, fresh, 60);
}

// A device that turns now and then: the pairs a proxy that did not turn
// was searched for (shifts alone) must not serve the first turn after, and
// those of a turn serve the shifts that follow. Down onto the crest and
// along it, turning by 0.02 rad every third step: each model built
// is the one a fresh search makes.
TEST(ToolStageTest, BuiltModelsAreTheSearchedOnesWhenTheDeviceTurnsAtTimes) {
  std::unique_ptr<Scene> kept = RemoteDeviceScene();
  std::unique_ptr<Scene> searched = RemoteDeviceScene();
  int built = 0, built_touching = 0;
  uint64_t last_revision = 0;
  double angle = 0;
  for (int step = 0; step < 60; ++step) {
    if (step % 3 == 2) angle += 2e-2;
    const double z = 0.095 - 0.0005 * std::min(step, 30);
    const double x = 0.1 - (step > 30 ? 0.0005 * (step - 30) : 0.0);
    Isometry3d X = At(x, 0, z);
    X.linear() = Eigen::AngleAxisd(angle, Vector3d(0.6, 0, 0.8)).toRotationMatrix();
    ASSERT_TRUE(kept->SetDevicePose(2, X).ok());
    ASSERT_TRUE(searched->SetDevicePose(2, X).ok());
    ASSERT_TRUE(searched->RequestLocalModel(2).ok());
    const LocalModel& model = kept->Step().tools[0].local_model;
    const LocalModel& fresh = searched->Step().tools[0].local_model;
    const bool new_model = model.revision != last_revision;
    last_revision = model.revision;
    if (!new_model || model.validity_radius_m < fresh.validity_radius_m) continue;  // anchored
    ++built;
    built_touching += model.touching;
    ExpectSamePlanes(model, fresh, step);
  }
  EXPECT_GT(built, 20);
  EXPECT_GT(built_touching, 10);
}

// Random presses and slides over the organ (fixed seeds): each model
// anchored along them holds the organ out (CheckHoldsOrganOut), whatever
// the direction and speed of the slide.
TEST(ToolStageTest, AnchoredModelsHoldTheOrganOutOnRandomSlides) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int anchored = 0;
  int checked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    std::unique_ptr<Scene> scene = RemoteDeviceScene();
    const double angle = 2 * std::numbers::pi * u(rng);
    const Vector3d along(std::cos(angle), std::sin(angle), 0);
    const double speed = 1e-4 + 9e-4 * u(rng);  // 0.1 to 1 mm a step
    const double depth = 0.001 + 0.004 * u(rng);
    uint64_t last_revision = 0;
    LocalModel last_built;
    for (int step = 0; step < 60; ++step) {
      const double z = std::max(0.095 - 0.0005 * step, 0.09 - depth);
      const double slid = step > 30 ? speed * (step - 30) : 0.0;
      const Vector3d p = Vector3d(0.1, 0, z) + slid * along;
      ASSERT_TRUE(scene->SetDevicePose(2, At(p.x(), p.y(), p.z())).ok());
      const LocalModel& model = scene->Step().tools[0].local_model;
      if (model.revision == last_revision) continue;
      last_revision = model.revision;
      if (model.validity_radius_m == 0.01) {
        last_built = model;
        continue;
      }
      ++anchored;
      checked += CheckHoldsOrganOut(model, last_built,
                                    model.X_WP.translation() - last_built.X_WP.translation(), step);
    }
  }
  EXPECT_GT(anchored, 20) << "the slides must anchor models";
  EXPECT_GT(checked, 100) << "points of the organ must be near the anchored models";
}

// The radius a device asks for is taken within the scene's bounds (its
// local_model_radius_m, 1 cm, and local_model_radius_cap_m, 4 cm) from the
// next step, 0 returns to the scene's, and the model is then the one a
// fresh search with that radius makes; a radius that is not finite or is
// negative is INVALID_ARGUMENT and changes nothing.
TEST(ToolStageTest, ADeviceSizesItsModelWithinTheScenesBounds) {
  std::unique_ptr<Scene> scene = RemoteDeviceScene();
  std::unique_ptr<Scene> searched = RemoteDeviceScene();
  const std::vector<std::pair<double, double>> asked_taken = {
      {0.02, 0.02}, {0.001, 0.01}, {0.5, 0.04}, {0, 0.01}, {0.03, 0.03}};
  double z = 0.095;
  for (const auto& [asked, taken] : asked_taken) {
    z -= 0.001;
    ASSERT_TRUE(scene->SetDevicePose(2, At(0.1, 0, z)).ok());
    ASSERT_TRUE(scene->SetLocalModelRadius(2, asked).ok());
    const LocalModel model = scene->Step().tools[0].local_model;
    EXPECT_EQ(model.validity_radius_m, taken) << asked;
    // The oracle: a scene whose own radius is `taken`, searched afresh.
    ASSERT_TRUE(searched->SetDevicePose(2, At(0.1, 0, z)).ok());
    ASSERT_TRUE(searched->SetLocalModelRadius(2, taken).ok());
    ASSERT_TRUE(searched->RequestLocalModel(2).ok());
    const LocalModel& fresh = searched->Step().tools[0].local_model;
    ASSERT_EQ(model.planes.size(), fresh.planes.size()) << asked;
    for (size_t i = 0; i < model.planes.size(); ++i) {
      EXPECT_EQ(model.planes[i].normal_W, fresh.planes[i].normal_W) << asked;
      EXPECT_EQ(model.planes[i].gap_m, fresh.planes[i].gap_m) << asked;
    }
  }
  for (double bad : {std::nan(""), -0.01, std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(scene->SetLocalModelRadius(2, bad).code(), absl::StatusCode::kInvalidArgument);
  }
  ASSERT_TRUE(scene->SetDevicePose(2, At(0.1, 0, z - 0.001)).ok());
  EXPECT_EQ(scene->Step().tools[0].local_model.validity_radius_m, 0.03);
  EXPECT_EQ(scene->SetLocalModelRadius(0, 0.02).code(), absl::StatusCode::kFailedPrecondition);
}

// A device that sends no changed pose costs no query: the steps run no
// stage and hold the last frame, until the device moves, a device asks for
// a fresh model or the needs change.
TEST(ToolStageTest, StillDevicesCostNoQuery) {
  std::unique_ptr<Scene> scene = RemoteDeviceScene();
  for (int step = 0; step < 12; ++step) {
    ASSERT_TRUE(scene->SetDevicePose(2, At(0.1, 0, 0.09 - 0.001 * step)).ok());
    scene->Step();
  }
  const StepFrame pressed = scene->Step();
  ASSERT_GT(pressed.tools[0].force_W.norm(), 0);  // pressing into the organ
  const int64_t runs = scene->stats()[static_cast<int>(Effect::kReversingVector)].runs;
  for (int step = 0; step < 10; ++step) {
    ASSERT_TRUE(scene->SetDevicePose(2, At(0.1, 0, 0.09 - 0.011)).ok());  // the same pose
    const StepFrame& still = scene->Step();
    EXPECT_EQ(still.stages_run, EffectSet());
    ExpectSameToolFrames(pressed, still);
  }
  EXPECT_EQ(scene->stats()[static_cast<int>(Effect::kReversingVector)].runs, runs);
  // An object added under the still probe may change what it touches.
  (void)*scene->AddObject(*HapticObject::Create("pad", MakeBox(Vector3d::Constant(0.01))),
                          ObjectKind::kFixed, At(0.1, 0, 0.075));
  EXPECT_TRUE(scene->Step().stages_run.Has(Effect::kReversingVector));
  EXPECT_EQ(scene->Step().stages_run, EffectSet());
  ASSERT_TRUE(scene->RequestLocalModel(2).ok());
  EXPECT_TRUE(scene->Step().stages_run.Has(Effect::kLocalModel));
  scene->SetNeeded(EffectSet::All());
  EXPECT_TRUE(scene->Step().stages_run.Has(Effect::kContactSet));
}

// The organ on its floor and a probe over each side of its crest, 20 cm
// apart (ids 2 and 3), with a remote device's needs; `both` false leaves
// the second probe out.
std::unique_ptr<Scene> ProbesApartScene(bool both) {
  std::unique_ptr<Scene> scene = *Scene::Create({});
  (void)*scene->AddObject(*HapticObject::Create("floor", MakeBox(Vector3d(1, 1, 0.05))),
                          ObjectKind::kFixed, At(0, 0, -0.025));
  (void)*scene->AddObject(*HapticObject::Create("organ", MakeTorus(0.1, 0.04, 48, 24)),
                          ObjectKind::kFixed, At(0, 0, 0.04));
  for (const double x : both ? std::vector{0.1, -0.1} : std::vector{0.1}) {
    (void)*scene->AddObject(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))),
                            ObjectKind::kTool, At(x, 0, 0.1));
  }
  scene->SetNeeded(EffectSet{Effect::kForce, Effect::kFriction, Effect::kLocalModel});
  return scene;
}

// A still tool costs no query while another tool far from it moves: after
// pressing into the organ, the first probe's device holds its pose while
// the second slides on the other side. The oracle: the first probe's
// frames are those of a scene where it is alone (whose still steps hold
// the whole frame), and the proxy stage runs once a step, for the second.
// When the second device comes within the first's reach, both step.
TEST(ToolStageTest, AStillToolCostsNoQueryWhileAnotherMoves) {
  std::unique_ptr<Scene> both = ProbesApartScene(true);
  std::unique_ptr<Scene> alone = ProbesApartScene(false);
  auto reversing_runs = [&] {
    return both->stats()[static_cast<int>(Effect::kReversingVector)].runs;
  };
  for (int step = 0; step < 30; ++step) {
    const Isometry3d first = At(0.1, 0, 0.09 - 0.001 * std::min(step, 11));
    ASSERT_TRUE(both->SetDevicePose(2, first).ok());
    ASSERT_TRUE(alone->SetDevicePose(2, first).ok());
    ASSERT_TRUE(both->SetDevicePose(3, At(-0.1 + 0.0005 * step, 0, 0.085)).ok());
    const int64_t runs = reversing_runs();
    const StepFrame& b = both->Step();
    const StepFrame& a = alone->Step();
    ExpectSameToolFrame(a.tools[0], b.tools[0]);
    if (step >= 13) {
      EXPECT_EQ(reversing_runs(), runs + 1) << step;
      EXPECT_GT(b.tools[0].force_W.norm(), 0);
    }
  }
  // The second device next to the first: they may meet, and both step.
  ASSERT_TRUE(both->SetDevicePose(3, At(0.1, 0.021, 0.1)).ok());
  const int64_t runs = reversing_runs();
  both->Step();
  EXPECT_EQ(reversing_runs(), runs + 2);
}

}  // namespace
}  // namespace hs
