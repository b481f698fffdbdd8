// Closed-loop runs of a remote device on the demo scene, in process and in
// simulated time (the scene steps once per 1 ms tick), so they repeat
// exactly: the hand presses the probe into the organ through a link of
// 100 ms round trip.

#include "client/remote/remote_run.h"

#include <gtest/gtest.h>

#include <string>

#include "common/api/proto_convert.h"
#include "common/api/scene_file.h"

namespace hs::cli {
namespace {

const std::string kScene = std::string(HS_SCENES_DIR) + "/probe_on_torus.textproto";

// The passivity bound of the study (docs/remote-haptics.md): the contact
// may hand back at most this much work to the hand over a run, joules.
constexpr double kPassiveBoundJ = 1e-3;

RemoteSummary RunPress(bool local_model, double latency_ms, double seconds,
                       std::vector<Vector3d>* forces = nullptr,
                       std::span<const Vector3d> reference = {}) {
  absl::StatusOr<haptics::v1::SceneSpec> spec = ReadSceneFile(kScene);
  absl::StatusOr<LoadedScene> loaded = LoadSceneFile(kScene);
  EXPECT_TRUE(spec.ok() && loaded.ok());
  Scene& scene = *loaded->scene;
  scene.SetNeeded({Effect::kForce, Effect::kFriction, Effect::kLocalModel, Effect::kContactSet,
                   Effect::kReversingVector});
  const ObjectId tool = FindTool(*loaded, "probe");
  Isometry3d start = Isometry3d::Identity();
  for (const auto& o : spec->objects()) {
    if (o.name() == "probe") start = *PoseFromProto(o.pose(), "pose");
  }
  RemoteRunOptions options;
  options.motion = OperatorMotion::kPress;
  options.local_model = local_model;
  options.link = {.latency_ms = latency_ms, .seed = 1};
  RemoteRun run(options, start);
  uint64_t applied = 0;
  const int64_t ticks = static_cast<int64_t>(seconds / options.tick_s);
  for (int64_t k = 0; k < ticks; ++k) {
    const double now = static_cast<double>(k) * options.tick_s;
    run.Tick(k);
    run.DeliverPoses(now, [&](const PoseMessage& pose) {
      EXPECT_TRUE(scene.SetDevicePose(tool, pose.X_WD).ok());
      applied = pose.sequence;
    });
    const ToolFrame& t = scene.Step().tools.front();
    ServerFrame frame{.applied_sequence = applied, .force_W = t.force_W, .model = t.local_model};
    for (const PairContact& c : t.contacts)
      frame.depth_m = std::max(frame.depth_m, c.contact.depth_m);
    run.FromServer(now, std::move(frame));
  }
  if (forces) *forces = run.forces();
  return run.Summary(reference);
}

// At 100 ms round trip the device rendering from the local model keeps the
// contact passive (it hands back no more work than the bound) and smooth
// (no tick changes the force by more than the switch bound and what the
// hand's own motion makes); applying the server's late forces instead puts
// energy into the hand.
TEST(RemoteRunTest, LocalModelKeepsAPressPassiveAt100Ms) {
  std::vector<Vector3d> reference;
  RunPress(true, 0, 4, &reference);
  const RemoteSummary local = RunPress(true, 100, 4, nullptr, reference);
  const RemoteSummary server = RunPress(false, 100, 4);
  std::cout << "local: energy " << local.energy_j << " J, max step " << local.max_force_step_n
            << " N, penetration p99 " << local.penetration_p99_m << " m, rms error "
            << local.force_rms_error_n << " N, max force " << local.max_force_n << " N\n"
            << "server: energy " << server.energy_j << " J, max step " << server.max_force_step_n
            << " N, penetration p99 " << server.penetration_p99_m << " m, max force "
            << server.max_force_n << " N\n";
  EXPECT_GT(local.max_force_n, 0.5) << "the press must reach the organ";
  EXPECT_LE(local.energy_j, kPassiveBoundJ);
  EXPECT_GT(server.energy_j, kPassiveBoundJ);
  EXPECT_NEAR(local.round_trip_p50_ms, 100, 2);
}

}  // namespace
}  // namespace hs::cli
