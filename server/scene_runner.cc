#include "server/scene_runner.h"

#include <pthread.h>
#include <sys/prctl.h>

#include <chrono>
#include <ctime>

#include <prometheus/counter.h>

#include "absl/strings/str_cat.h"
#include "common/api/scene_geometry.h"
#include "common/core/check.h"
#include "common/sim/frame_storage.h"
#include "server/step_pacer.h"
#include "server/thread_priority.h"

namespace hs {
namespace {

using Clock = std::chrono::steady_clock;

// CPU time the calling thread has used, nanoseconds.
int64_t ThreadCpuNanoseconds() {
  timespec t{};
  HS_CHECK(clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) == 0);
  return int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

int64_t Nanoseconds(Clock::duration d) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(d).count();
}

int64_t NowNanoseconds() { return Nanoseconds(Clock::now().time_since_epoch()); }

Clock::time_point AtNanoseconds(int64_t ns) {
  return Clock::time_point(
      std::chrono::duration_cast<Clock::duration>(std::chrono::nanoseconds(ns)));
}

SceneTools ToolsOf(const LoadedScene& scene) {
  SceneTools tools{.tools = {}, .object_count = scene.names.size()};
  for (const ObjectId id : scene.tools) tools.tools.emplace_back(scene.names[id], id);
  return tools;
}

}  // namespace

SceneRunner::SceneRunner(haptics::v1::SceneSpec spec, LoadedScene scene, Metrics& metrics,
                         const RunnerOptions& options, std::unique_ptr<SessionRecorder> recorder)
    : metrics_(metrics),
      step_s_(scene.scene->options().step_s),
      device_timeout_s_(options.device_timeout_s),
      device_timeout_status_(absl::DeadlineExceededError(absl::StrCat(
          "no pose came for ", options.device_timeout_s, " s: the tool is released where it was"))),
      name_(spec.name()),
      spec_(std::move(spec)),
      loaded_(std::move(scene)),
      names_(std::make_shared<const std::vector<std::string>>(loaded_.names)),
      applied_(loaded_.names.size()),
      recorder_(std::move(recorder)),
      streams_(ToolsOf(loaded_)),
      fan_out_(streams_, metrics, options.realtime_priority) {
  loaded_.scene->SetNeeded(EffectSet());
  // Should no thread be had, fan_out_ stops as the members go.
  thread_ = std::thread([this, priority = options.realtime_priority] { Run(priority); });
}

SceneRunner::~SceneRunner() { Stop(absl::UnavailableError("the scene was deleted")); }

void SceneRunner::Stop(const absl::Status& status) {
  CheckNotInSinkCall();
  {
    std::lock_guard lock(wake_mu_);
    if (stop_) return;
    stop_ = true;
    stop_status_ = status;
  }
  wake_cv_.notify_all();
  thread_.join();
}

void SceneRunner::CheckNotInSinkCall() {
  // A stream calling back from Offer or Close would wait for its own call
  // (Detach) or take the runner's locks from inside the frames' round.
  HS_CHECK(!FrameFanOut::InSinkCall() && "a FrameSink called back into its SceneRunner");
}

void SceneRunner::WakeIfDevicesFresh(const StreamChange& change) {
  if (!change.devices_fresh_since) return;
  {
    std::lock_guard lock(wake_mu_);
    devices_fresh_since_ = std::max(devices_fresh_since_, *change.devices_fresh_since);
  }
  wake_cv_.notify_all();
}

void SceneRunner::Run(int realtime_priority) {
  // Named so that `top -H` and profilers tell the stepping thread apart.
  pthread_setname_np(pthread_self(), "scene-step");
  // Wake-ups on time: the kernel's default timer slack (50 us) is half a
  // 10 kHz period.
  prctl(PR_SET_TIMERSLACK, 1UL);
  // Checked when the server started; should the system refuse now, the
  // scene steps at the default scheduler, as without the option.
  if (realtime_priority != 0) (void)SetRealtimePriority(realtime_priority);
  const int64_t period_ns = Nanoseconds(
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(step_s_)));
  StepPacer pacer(period_ns, NowNanoseconds(), ThreadCpuNanoseconds());
  absl::Status status;
  while (true) {
    bool devices_clocked = false;
    {
      std::unique_lock lock(wake_mu_);
      const auto devices_fresh = [this] { return devices_fresh_since_ >= last_take_; };
      while (!stop_) {
        const int64_t start_ns = pacer.start_ns(devices_fresh());
        if (NowNanoseconds() >= start_ns) break;
        wake_cv_.wait_until(lock, AtNanoseconds(start_ns));
      }
      if (stop_) {
        status = stop_status_;
        break;
      }
      devices_clocked = devices_fresh();
    }
    const StepPacer::Start start =
        pacer.StepStarts(NowNanoseconds(), ThreadCpuNanoseconds(), devices_clocked);
    if (start.missed > 0) {
      missed_steps_ += start.missed;
      if (start.off_cpu) missed_steps_off_cpu_ += start.missed;
      metrics_.AddMissedSteps(start.missed, start.off_cpu);
    }
    pacer.StepEnded(StepOnce(start.lag_ns));
  }
  StepOnce(0);  // the final frame
  fan_out_.Stop();
  streams_.CloseAll(status);
  fan_out_.HandOverEnds();
}

void SceneRunner::EndSilentDevices() {
  if (device_timeout_s_ <= 0) return;
  released_.clear();
  WakeIfDevicesFresh(streams_.EndSilentDevices(
      Clock::now() - std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(device_timeout_s_)),
      device_timeout_status_, released_));
  for (const std::string& tool : released_) RecordStream(false, tool, EffectSet());
}

int64_t SceneRunner::StepOnce(int64_t start_lag_ns) {
  EndSilentDevices();
  SnapshotPool::Slot& slot = snapshots_.Take();
  StepSnapshot* snapshot = slot.snapshot.get();
  int64_t step_ns = 0;
  {
    std::lock_guard lock(scene_mu_);
    // Under scene_mu_: the poses' tool ids are this scene's (Replace
    // re-maps the registry under it too).
    const EffectSet needs = streams_.TakeFreshPoses(fresh_);
    {
      std::lock_guard wake(wake_mu_);
      last_take_ = fresh_.generation;
    }
    Scene& scene = *loaded_.scene;
    snapshot->inputs.clear();
    for (const auto& [id, pose] : fresh_.taken()) {
      // Poses are validated at the edge.
      if (!ApplyDevicePose(scene, id, pose.X_WD, pose.seat).ok()) continue;
      // `id` is a tool and the radius was checked at the edge.
      (void)ApplyLocalModelRequest(scene, id, pose.model);
      applied_[id] = pose;
      snapshot->inputs.push_back({id, pose.X_WD, pose.stamp, pose.seat, pose.model});
    }
    snapshot->needs = needs;
    scene.SetNeeded(needs);
    const Clock::time_point start = Clock::now();
    const StepFrame& frame = scene.Step();
    step_ns = Nanoseconds(Clock::now() - start);
    snapshot->step_ns = step_ns;
    snapshot->step = ++step_;
    snapshot->time_s = static_cast<double>(step_) * step_s_;
    CopyFrame(frame, snapshot->frame, slot.storage);
    snapshot->names = names_;
    snapshot->holders = fresh_.holders;
    snapshot->applied.clear();
    for (const ToolFrame& t : frame.tools) {
      const std::optional<PendingPose>& applied = applied_[t.tool];
      snapshot->applied.push_back(applied ? applied->stamp : AppliedPose{});
    }
    StageStatsTable delta;
    for (int i = 0; i < kNumEffects; ++i) {
      delta[i].runs = scene.stats()[i].runs - last_stats_[i].runs;
      delta[i].total_ns = scene.stats()[i].total_ns - last_stats_[i].total_ns;
    }
    last_stats_ = scene.stats();
    metrics_.ObserveStep(1e-9 * static_cast<double>(snapshot->step_ns), delta);
    for (const ToolClash& clash : frame.clashes) {
      if (!clash.touching) continue;
      auto [at, added] = clash_counters_.try_emplace({clash.tool_a, clash.tool_b});
      if (added) {
        at->second = metrics_.ToolClashCountersFor(name_, loaded_.names[clash.tool_a],
                                                   loaded_.names[clash.tool_b]);
      }
      if (clash.began) at->second.clashes->Increment();
      at->second.seconds->Increment(step_s_);
    }
    snapshot->start_lag_ns = start_lag_ns;
    snapshot->missed_steps = missed_steps_;
    snapshot->missed_steps_off_cpu = missed_steps_off_cpu_;
    if (recorder_) recorder_->RecordStep(slot.snapshot);
  }
  fan_out_.Push(slot.snapshot);
  return step_ns;
}

absl::Status SceneRunner::AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                                       const absl::Status* take_over) {
  CheckNotInSinkCall();
  bool displaced = false;
  absl::Status status = streams_.AttachDevice(sink, claim, take_over, &displaced);
  if (displaced) RecordStream(false, claim.tool, EffectSet());
  if (status.ok()) RecordStream(true, claim.tool, claim.needs);
  return status;
}

absl::Status SceneRunner::AttachViewer(FrameSink* sink, EffectSet needs) {
  CheckNotInSinkCall();
  absl::Status status = streams_.AttachViewer(sink, needs);
  if (status.ok()) RecordStream(true, "", needs);
  return status;
}

void SceneRunner::RecordStream(bool attached, const std::string& tool, EffectSet needs) {
  if (!recorder_) return;
  std::lock_guard lock(scene_mu_);
  recorder_->RecordStream(step_, attached, !tool.empty(), tool, needs);
}

void SceneRunner::Detach(FrameSink* sink) {
  CheckNotInSinkCall();
  const StreamChange change = streams_.Detach(sink);
  if (change.tool) RecordStream(false, *change.tool, EffectSet());
  WakeIfDevicesFresh(change);
  // A call to `sink` that started before it left the registry ends first.
  fan_out_.WaitForSinkCalls();
}

void SceneRunner::SetDevicePose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp,
                                const LocalModelRequest& model) {
  CheckNotInSinkCall();
  WakeIfDevicesFresh(streams_.SetPose(sink, X_WD, stamp, model));
}

haptics::v1::SceneSpec SceneRunner::spec() const {
  std::lock_guard lock(scene_mu_);
  return spec_;
}

absl::Status SceneRunner::Replace(haptics::v1::SceneSpec spec, LoadedScene scene) {
  CheckNotInSinkCall();
  std::lock_guard lock(scene_mu_);
  if (absl::Status s = streams_.RemapTools(ToolsOf(scene)); !s.ok()) return s;
  // Tools keep where their devices put them; the proxies start over there.
  std::vector<std::optional<PendingPose>> applied(scene.names.size());
  for (size_t old_id = 0; old_id < applied_.size(); ++old_id) {
    if (!applied_[old_id]) continue;
    const ObjectId id = FindTool(scene, loaded_.names[old_id]);
    if (id >= 0 && scene.scene->SetDevicePose(id, applied_[old_id]->X_WD).ok()) {
      applied[id] = applied_[old_id];
    }
  }
  applied_ = std::move(applied);
  // The old scene goes with `scene` once the lock is released: tearing
  // down its meshes and threads must not hold up the steps.
  std::swap(spec_, spec);
  std::swap(loaded_, scene);
  names_ = std::make_shared<const std::vector<std::string>>(loaded_.names);
  clash_counters_.clear();  // the ids are the new scene's
  last_stats_ = StageStatsTable{};
  ++revision_;
  if (recorder_) recorder_->RecordEdit(step_, spec_, revision_);
  return absl::OkStatus();
}

void SceneRunner::Geometry(haptics::v1::SceneGeometry* out) const {
  std::lock_guard lock(scene_mu_);
  SceneGeometryToProto(*loaded_.scene, loaded_.names, revision_, out);
  out->set_scene(spec_.name());
}

RunnerInfo SceneRunner::Info() const {
  RunnerInfo info;
  StreamRegistry::Counts counts = streams_.counts();
  info.devices = counts.devices;
  info.viewers = counts.viewers;
  info.claimed_tools = std::move(counts.claimed_tools);
  std::lock_guard lock(scene_mu_);
  info.spec = spec_;
  info.step = step_;
  info.triangles = loaded_.triangles;
  info.revision = revision_;
  return info;
}

}  // namespace hs
