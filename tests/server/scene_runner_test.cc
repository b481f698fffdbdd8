#include "server/scene_runner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "common/core/check.h"
#include "server/thread_priority.h"
#include "tests/server/realtime_on_cpu.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

// Keeps what the runner hands over, for the test thread to wait on.
class RecordingSink : public FrameSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    std::lock_guard lock(mu_);
    last_ = std::move(snapshot);
    ++offers_;
    cv_.notify_all();
  }
  void Close(const absl::Status& status) override {
    std::lock_guard lock(mu_);
    closed_ = status;
    ++closes_;
    cv_.notify_all();
  }
  // The latest snapshot once `n` or more have been offered in all.
  std::shared_ptr<const StepSnapshot> WaitForOffers(int n) {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return offers_ >= n; });
    return last_;
  }
  // The status the sink was closed with, once it is.
  absl::Status WaitForClose() {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return closes_ > 0; });
    return closed_;
  }
  int offers() {
    std::lock_guard lock(mu_);
    return offers_;
  }
  int closes() {
    std::lock_guard lock(mu_);
    return closes_;
  }
  absl::Status closed() {
    std::lock_guard lock(mu_);
    return closed_;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::shared_ptr<const StepSnapshot> last_;
  int offers_ = 0;
  int closes_ = 0;
  absl::Status closed_;
};

// Who holds which tool at the step of `s`, by tool name.
std::map<std::string, std::string> HolderNames(const StepSnapshot& s) {
  std::map<std::string, std::string> holders;
  for (size_t id = 0; id < s.holders->size(); ++id) {
    if ((*s.holders)[id].sink != nullptr) holders[(*s.names)[id]] = (*s.holders)[id].name;
  }
  return holders;
}

// A stream that breaks FrameSink's contract: it calls its runner back from
// Offer.
class CallingBackSink : public FrameSink {
 public:
  explicit CallingBackSink(SceneRunner*& runner) : runner_(runner) {}
  void Offer(std::shared_ptr<const StepSnapshot>) override {
    runner_->SetDevicePose(this, Isometry3d::Identity(), AppliedPose{});
  }
  void Close(const absl::Status&) override {}

 private:
  SceneRunner*& runner_;
};

std::unique_ptr<SceneRunner> Runner(Metrics& metrics) {
  const haptics::v1::SceneSpec spec = testing::SmallScene("r", /*second_tool=*/true);
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, "");
  EXPECT_TRUE(loaded.ok());
  return std::make_unique<SceneRunner>(spec, std::move(loaded).value(), metrics);
}

// A device's pose is applied at the next step and stamped with its
// sequence; a second device on the same tool is FAILED_PRECONDITION, an
// unknown tool NOT_FOUND.
TEST(SceneRunnerTest, PosesAppliedAndToolsHeldOnce) {
  Metrics metrics;
  RecordingSink device, other;  // outlive the runner, which offers its last frame
  auto runner = Runner(metrics);
  ASSERT_TRUE(runner->AttachDevice(&device, {"probe", EffectSet::All()}).ok());
  EXPECT_EQ(runner->AttachDevice(&other, {"probe", EffectSet()}).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(runner->AttachDevice(&other, {"table", EffectSet()}).code(),
            absl::StatusCode::kNotFound);
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0, 0, 0.0195);
  runner->SetDevicePose(&device, X, AppliedPose{7, 123});
  std::shared_ptr<const StepSnapshot> s;
  for (int n = 1; n < 1000; ++n) {
    s = device.WaitForOffers(n);
    if (!s->applied.empty() && s->applied[0].sequence == 7) break;
  }
  ASSERT_EQ(s->frame.tools.size(), 2u);
  EXPECT_EQ(s->applied[0].device_time_ns, 123);
  EXPECT_TRUE(s->frame.tools[0].X_WD.isApprox(X, 0.0));
  EXPECT_EQ(s->frame.tools[0].contacts.size(), 1u);  // the probe presses on the table
  runner->Detach(&device);
  EXPECT_EQ(runner->Info().devices, 0);
}

// The stylus's device goes into the probe: the frames hold the pair's
// clash, and /metrics counts it for the scene by tool names.
TEST(SceneRunnerTest, ToolClashesReachFramesAndMetrics) {
  Metrics metrics;
  RecordingSink stylus;  // outlives the runner, which offers its last frame
  auto runner = Runner(metrics);
  ASSERT_TRUE(runner->AttachDevice(&stylus, {"stylus", EffectSet::All()}).ok());
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.015, 0, 0.05);  // 5 mm into the probe at its home
  runner->SetDevicePose(&stylus, X, AppliedPose{1, 0});
  std::shared_ptr<const StepSnapshot> s;
  for (int n = 1; n < 1000; ++n) {
    s = stylus.WaitForOffers(n);
    if (!s->applied.empty() && s->applied[1].sequence == 1) break;
  }
  ASSERT_EQ(s->frame.clashes.size(), 1u);
  EXPECT_EQ(s->frame.clashes[0].count, 1);
  EXPECT_TRUE(s->frame.clashes[0].touching);
  runner.reset();
  EXPECT_NE(metrics.Text().find(
                "hs_tool_clashes_total{scene=\"r\",tool_a=\"probe\",tool_b=\"stylus\"} 1"),
            std::string::npos)
      << metrics.Text();
}

// Frames name the holder of each held tool. A device that sends no pose
// for the timeout is ended DEADLINE_EXCEEDED and its tool released: the
// tool stays where its last pose put it, proxy and all, and another device
// may take it.
TEST(SceneRunnerTest, ASilentDeviceReleasesItsToolWhereItWas) {
  Metrics metrics;
  RecordingSink device, viewer, next;  // outlive the runner, which offers its last frame
  const haptics::v1::SceneSpec spec = testing::SmallScene("r");
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, "");
  ASSERT_TRUE(loaded.ok());
  SceneRunner runner(spec, *std::move(loaded), metrics, {.device_timeout_s = 0.2});
  ASSERT_TRUE(runner.AttachViewer(&viewer, EffectSet::All()).ok());
  ASSERT_TRUE(runner.AttachDevice(&device, {"probe", EffectSet::All(), "alice"}).ok());
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(0.03, 0.01, 0.0195);  // pressing on the table
  runner.SetDevicePose(&device, X, AppliedPose{1, 0});
  std::shared_ptr<const StepSnapshot> held;
  for (int n = 1; n < 1000; ++n) {
    held = viewer.WaitForOffers(n);
    if (held->applied[0].sequence == 1) break;
  }
  // A few steps on, the proxy has finished its slide onto the table.
  held = viewer.WaitForOffers(viewer.offers() + 5);
  ASSERT_NE(held->holders, nullptr);
  EXPECT_EQ(HolderNames(*held), (std::map<std::string, std::string>{{"probe", "alice"}}));
  const absl::Status ended = device.WaitForClose();
  EXPECT_EQ(ended.code(), absl::StatusCode::kDeadlineExceeded) << ended;
  EXPECT_EQ(runner.Info().devices, 0);
  const std::shared_ptr<const StepSnapshot> released = viewer.WaitForOffers(viewer.offers() + 2);
  EXPECT_TRUE(HolderNames(*released).empty());
  EXPECT_TRUE(released->frame.tools[0].X_WD.isApprox(X, 0.0));
  EXPECT_TRUE(released->frame.tools[0].X_WP.isApprox(held->frame.tools[0].X_WP, 0.0));
  EXPECT_FALSE(released->frame.tools[0].contacts.empty());  // still on the table
  EXPECT_TRUE(runner.AttachDevice(&next, {"probe", EffectSet::All(), "bob"}).ok());
}

// Replacing the scene keeps step ids going and refuses (changing nothing)
// a scene without a held tool; Stop sends a last frame and closes every
// sink once with the given status.
TEST(SceneRunnerTest, ReplaceAndStop) {
  Metrics metrics;
  RecordingSink device;  // outlives the runner, which offers its last frame
  auto runner = Runner(metrics);
  ASSERT_TRUE(runner->AttachDevice(&device, {"stylus", EffectSet::All()}).ok());
  const int64_t before = device.WaitForOffers(3)->step;

  haptics::v1::SceneSpec without_stylus = testing::SmallScene("r");
  absl::StatusOr<LoadedScene> loaded = BuildScene(without_stylus, "");
  ASSERT_TRUE(loaded.ok());
  EXPECT_EQ(runner->Replace(without_stylus, std::move(loaded).value()).code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(runner->Info().revision, 0);

  haptics::v1::SceneSpec same = testing::SmallScene("r", true);
  loaded = BuildScene(same, "");
  ASSERT_TRUE(loaded.ok());
  ASSERT_TRUE(runner->Replace(same, std::move(loaded).value()).ok());
  EXPECT_EQ(runner->Info().revision, 1);
  EXPECT_GT(device.WaitForOffers(device.offers() + 1)->step, before);

  runner->Stop(absl::UnavailableError("bye"));
  EXPECT_EQ(device.closes(), 1);
  EXPECT_EQ(device.closed().code(), absl::StatusCode::kUnavailable);
  RecordingSink late;
  EXPECT_EQ(runner->AttachViewer(&late, EffectSet()).code(), absl::StatusCode::kUnavailable);
}

// Devices clock the steps: while one of two devices is silent the scene
// keeps its period (2 s here); once both have sent, it steps without waiting
// for the period's end, though not sooner than 3/4 of it after the last step,
// and after such a step a device a little late still joins the next one.
TEST(SceneRunnerTest, DevicesClockTheSteps) {
  using Clock = std::chrono::steady_clock;
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  Metrics metrics;
  haptics::v1::SceneSpec spec = testing::SmallScene("r", /*second_tool=*/true);
  spec.set_step_s(2.0);
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, "");
  ASSERT_TRUE(loaded.ok());
  const Clock::time_point start = Clock::now();
  RecordingSink probe, stylus;  // outlive the runner, which offers its last frame
  // The stylus is silent for 4 s, longer than the default device timeout.
  SceneRunner runner(spec, std::move(loaded).value(), metrics, {.device_timeout_s = 0});
  ASSERT_TRUE(runner.AttachDevice(&probe, {"probe", EffectSet()}).ok());
  ASSERT_TRUE(runner.AttachDevice(&stylus, {"stylus", EffectSet()}).ok());
  const Isometry3d X = Isometry3d::Identity();
  runner.SetDevicePose(&probe, X, AppliedPose{1, 0});
  EXPECT_EQ(probe.WaitForOffers(1)->applied[0].sequence, 1u);
  EXPECT_GE(seconds_since(start), 1.8);  // the stylus is silent: the period's end

  const Clock::time_point second = Clock::now();
  runner.SetDevicePose(&probe, X, AppliedPose{2, 0});
  runner.SetDevicePose(&stylus, X, AppliedPose{1, 0});
  const std::shared_ptr<const StepSnapshot> s = probe.WaitForOffers(2);
  const double waited = seconds_since(second);
  EXPECT_LT(waited, 1.9);  // both sent: about 1.5 s, not the period's 2 s
  EXPECT_GE(waited, 1.3);
  ASSERT_EQ(s->applied.size(), 2u);
  EXPECT_EQ(s->applied[0].sequence, 2u);
  EXPECT_EQ(s->applied[1].sequence, 1u);

  // After a step the devices clocked, a pose a little late (a tenth of a
  // period past the period's end) still joins the next step: its deadline
  // is a quarter period past the period's end.
  const Clock::time_point third = Clock::now();
  runner.SetDevicePose(&probe, X, AppliedPose{3, 0});
  std::this_thread::sleep_until(third + std::chrono::milliseconds(2100));
  EXPECT_EQ(probe.offers(), 2);  // no step at the period's end without the stylus
  runner.SetDevicePose(&stylus, X, AppliedPose{2, 0});
  const std::shared_ptr<const StepSnapshot> late = probe.WaitForOffers(3);
  EXPECT_LT(seconds_since(third), 2.45);  // at once, not at the deadline (2.5 s)
  ASSERT_EQ(late->applied.size(), 2u);
  EXPECT_EQ(late->applied[0].sequence, 3u);
  EXPECT_EQ(late->applied[1].sequence, 2u);
}

// A runner stepping `spec` with a viewer attached, for the missed-step tests.
struct ViewedRunner {
  explicit ViewedRunner(const haptics::v1::SceneSpec& spec) {
    absl::StatusOr<LoadedScene> loaded = BuildScene(spec, "");
    HS_CHECK(loaded.ok());
    runner = std::make_unique<SceneRunner>(spec, std::move(loaded).value(), metrics);
    HS_CHECK(runner->AttachViewer(&viewer, EffectSet()).ok());
  }
  Metrics metrics;
  RecordingSink viewer;  // outlives the runner, which offers its last frame
  std::unique_ptr<SceneRunner> runner;
};

// A scene whose step outlasts its period (1 us here) misses steps while it
// steps: none of them counts as off the CPU, whatever else runs. (It
// guards the direction of the test, the comparison itself is the next.)
TEST(SceneRunnerTest, StepsMissedComputingAreNotOffCpu) {
  haptics::v1::SceneSpec spec = testing::SmallScene("r");
  spec.set_step_s(1e-6);
  ViewedRunner viewed(spec);
  const std::shared_ptr<const StepSnapshot> s = viewed.viewer.WaitForOffers(200);
  EXPECT_GT(s->missed_steps, 0);
  EXPECT_EQ(s->missed_steps_off_cpu, 0);
}

// Real-time threads spinning on every CPU this process may use, all at
// once, keep a scene thread at the default scheduler off the CPU for
// 50 ms: the 1 kHz scene misses about 50 steps, off the CPU unless the
// spin began mid-step (its ~0.03 ms of each 1 ms; then they count as
// stepping). Twice, so that at least one spell counts. Needs real-time
// scheduling (root or CAP_SYS_NICE); bounded by the spins, far below
// Linux's throttling.
TEST(SceneRunnerTest, StepsMissedWaitingForACpuAreOffCpu) {
  if (!CheckRealtimePriority(50).ok()) GTEST_SKIP() << "no real-time scheduling here";
  const std::vector<int> cpus = testing::AllowedCpus();
  ASSERT_FALSE(cpus.empty());
  ViewedRunner viewed(testing::SmallScene("r"));
  viewed.viewer.WaitForOffers(5);
  for (int spell = 0; spell < 2; ++spell) {
    // Each spinner is ready (real-time, on its CPU) before any spins: a
    // spinner started late would leave the scene a CPU meanwhile.
    std::mutex mu;
    std::condition_variable cv;
    int ready = 0, refused = 0;
    bool go = false;
    std::vector<std::thread> spinners;
    for (int cpu : cpus) {
      spinners.emplace_back([&, cpu] {
        const bool ok = testing::RunOnCpuAt(cpu, 50);
        {
          std::unique_lock lock(mu);
          ++ready;
          refused += !ok;
          cv.notify_all();
          cv.wait(lock, [&] { return go; });
        }
        if (!ok) return;
        const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
        while (std::chrono::steady_clock::now() < end) {
        }
      });
    }
    {
      std::unique_lock lock(mu);
      cv.wait(lock, [&] { return ready == static_cast<int>(cpus.size()); });
      go = true;
      cv.notify_all();
    }
    for (std::thread& t : spinners) t.join();
    ASSERT_EQ(refused, 0) << "a spinner could not take its CPU";
  }
  const std::shared_ptr<const StepSnapshot> s =
      viewed.viewer.WaitForOffers(viewed.viewer.offers() + 5);
  EXPECT_GE(s->missed_steps_off_cpu, 30);
  EXPECT_LE(s->missed_steps_off_cpu, s->missed_steps);
}

// A stream calling back into its runner from Offer aborts with a message
// (it would otherwise take the runner's locks inside the frames' round).
TEST(SceneRunnerDeathTest, AStreamCallingBackAborts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        Metrics metrics;
        SceneRunner* runner = nullptr;
        CallingBackSink sink(runner);
        std::unique_ptr<SceneRunner> owned = Runner(metrics);
        runner = owned.get();
        (void)runner->AttachViewer(&sink, EffectSet());
        for (;;) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      },
      "a FrameSink called back into its SceneRunner");
}

}  // namespace
}  // namespace hs
