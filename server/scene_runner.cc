#include "server/scene_runner.h"

#include <pthread.h>

#include <chrono>
#include <ctime>

#include "absl/strings/str_cat.h"
#include "common/core/check.h"
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

// The id of tool `name` in `scene`, or -1.
ObjectId FindTool(const LoadedScene& scene, const std::string& name) {
  for (ObjectId id : scene.tools) {
    if (scene.names[id] == name) return id;
  }
  return -1;
}

}  // namespace

SceneRunner::SceneRunner(haptics::v1::SceneSpec spec, LoadedScene scene, Metrics& metrics,
                         int realtime_priority)
    : metrics_(metrics),
      step_s_(scene.scene->options().step_s),
      spec_(std::move(spec)),
      loaded_(std::move(scene)),
      names_(std::make_shared<const std::vector<std::string>>(loaded_.names)) {
  loaded_.scene->SetNeeded(EffectSet());
  fanout_thread_ = std::thread([this, realtime_priority] { FanOut(realtime_priority); });
  try {
    thread_ = std::thread([this, realtime_priority] { Run(realtime_priority); });
  } catch (...) {  // no thread to be had: stop the first, not std::terminate
    StopFanOut();
    throw;
  }
}

SceneRunner::~SceneRunner() { Stop(absl::UnavailableError("the scene was deleted")); }

void SceneRunner::Stop(const absl::Status& status) {
  {
    std::lock_guard lock(stop_mu_);
    if (stop_) return;
    stop_ = true;
    stop_status_ = status;
  }
  stop_cv_.notify_all();
  thread_.join();
}

void SceneRunner::Run(int realtime_priority) {
  // Named so that `top -H` and profilers tell the stepping thread apart.
  pthread_setname_np(pthread_self(), "scene-step");
  // Checked when the server started; should the system refuse now, the
  // scene steps at the default scheduler, as without the option.
  if (realtime_priority != 0) (void)SetRealtimePriority(realtime_priority);
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(step_s_));
  const int64_t period_ns = Nanoseconds(period);
  // A device faster than the scene's rate speeds it up by 4/3 at most.
  const Clock::duration shortest = period * 3 / 4;
  Clock::time_point last = Clock::now();
  int64_t cpu_at_last = ThreadCpuNanoseconds();
  int64_t last_step_ns = 0;
  Clock::time_point next = last + period;  // the deadline of the next step
  absl::Status status;
  while (true) {
    bool early = false;
    {
      std::unique_lock lock(stop_mu_);
      // Not sooner than `shortest` after the last step; then at the
      // deadline, or once every device has sent.
      stop_cv_.wait_until(lock, std::min(next, last + shortest), [this] { return stop_; });
      stop_cv_.wait_until(lock, next, [this] { return stop_ || devices_fresh_; });
      if (stop_) {
        status = stop_status_;
        break;
      }
      early = devices_fresh_;
    }
    const Clock::time_point now = Clock::now();
    const int64_t cpu_now = ThreadCpuNanoseconds();
    const Clock::duration lag = now - next;  // negative when the devices came first
    if (lag > period) {
      // Too late to catch up: skip the missed steps rather than run a burst.
      const int64_t missed = lag / period;
      // Having run for less than a period since the last step began, after
      // a step shorter than a period (wall time, so its workers' share
      // too), this thread lost the time waiting (for a core, a lock or its
      // wake-up), not stepping. All of one late wake-up's misses count alike.
      const bool off_cpu = cpu_now - cpu_at_last < period_ns && last_step_ns < period_ns;
      missed_steps_ += missed;
      if (off_cpu) missed_steps_off_cpu_ += missed;
      metrics_.AddMissedSteps(missed, off_cpu);
      next += missed * period;
    }
    last_step_ns = StepOnce(std::max<int64_t>(Nanoseconds(lag), 0));
    last = now;
    cpu_at_last = cpu_now;
    // Devices that came first set the phase from now on, and their next
    // poses are due one period later: the deadline falls a quarter period
    // after that, so that a pose a little late joins its step instead of
    // waiting a whole period for the next.
    next = early ? now + period + period / 4 : next + period;
  }
  StepOnce(0);  // the final frame
  StopFanOut();
  std::lock_guard lock(io_mu_);
  stopping_ = true;
  for (auto& [sink, attached] : sinks_) sink->Close(status);
}

int64_t SceneRunner::StepOnce(int64_t start_lag_ns) {
  std::vector<std::pair<std::string, PendingPose>> fresh;
  EffectSet needs;
  {
    std::lock_guard lock(io_mu_);
    for (auto& [tool, pose] : pending_) {
      if (!pose.fresh) continue;
      fresh.emplace_back(tool, pose);
      pose.fresh = false;
    }
    needs = NeedsLocked();
    std::lock_guard stop(stop_mu_);
    devices_fresh_ = false;
  }
  auto snapshot = std::make_shared<StepSnapshot>();
  int64_t step_ns = 0;
  {
    std::lock_guard lock(scene_mu_);
    Scene& scene = *loaded_.scene;
    for (const auto& [tool, pose] : fresh) {
      const ObjectId id = FindTool(loaded_, tool);
      // Poses are validated at the edge; a tool removed meanwhile is skipped.
      if (id < 0 || !scene.SetDevicePose(id, pose.X_WD).ok()) continue;
      applied_[tool] = pose;
    }
    scene.SetNeeded(needs);
    const Clock::time_point start = Clock::now();
    const StepFrame& frame = scene.Step();
    step_ns = Nanoseconds(Clock::now() - start);
    snapshot->step_ns = step_ns;
    snapshot->step = ++step_;
    snapshot->time_s = static_cast<double>(step_) * step_s_;
    snapshot->frame = frame;
    snapshot->names = names_;
    for (const ToolFrame& t : frame.tools) {
      const auto it = applied_.find(loaded_.names[t.tool]);
      snapshot->applied.push_back(it == applied_.end() ? AppliedPose{} : it->second.stamp);
    }
    StageStatsTable delta;
    for (int i = 0; i < kNumEffects; ++i) {
      delta[i].runs = scene.stats()[i].runs - last_stats_[i].runs;
      delta[i].total_ns = scene.stats()[i].total_ns - last_stats_[i].total_ns;
    }
    last_stats_ = scene.stats();
    metrics_.ObserveStep(1e-9 * static_cast<double>(snapshot->step_ns), delta);
  }
  snapshot->start_lag_ns = start_lag_ns;
  snapshot->missed_steps = missed_steps_;
  snapshot->missed_steps_off_cpu = missed_steps_off_cpu_;
  {
    std::lock_guard lock(fanout_mu_);
    if (fanout_queue_.size() >= kMaxQueuedFrames) {
      fanout_queue_.pop_front();
      metrics_.AddFramesDropped(1);
    }
    fanout_queue_.push_back(std::move(snapshot));
  }
  fanout_cv_.notify_one();
  return step_ns;
}

void SceneRunner::StopFanOut() {
  {
    std::lock_guard lock(fanout_mu_);
    fanout_stop_ = true;
  }
  fanout_cv_.notify_all();
  fanout_thread_.join();  // every frame queued is handed over first
}

void SceneRunner::FanOut(int realtime_priority) {
  pthread_setname_np(pthread_self(), "scene-frames");
  if (realtime_priority != 0) (void)SetRealtimePriority(realtime_priority);  // as Run
  std::unique_lock lock(fanout_mu_);
  while (true) {
    fanout_cv_.wait(lock, [this] { return fanout_stop_ || !fanout_queue_.empty(); });
    if (fanout_queue_.empty()) return;  // stopped, and every frame handed over
    std::shared_ptr<const StepSnapshot> snapshot = std::move(fanout_queue_.front());
    fanout_queue_.pop_front();
    lock.unlock();
    {
      std::lock_guard offering(offer_mu_);
      offer_to_.clear();
      {
        std::lock_guard io(io_mu_);
        for (const auto& [sink, attached] : sinks_) offer_to_.push_back(sink);
      }
      for (FrameSink* sink : offer_to_) sink->Offer(snapshot);
    }
    lock.lock();
  }
}

bool SceneRunner::DevicesFreshLocked() const {
  bool any = false;
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool.empty()) continue;
    const auto it = pending_.find(attached.tool);
    if (it == pending_.end() || !it->second.fresh) return false;
    any = true;
  }
  return any;
}

EffectSet SceneRunner::NeedsLocked() const {
  EffectSet needs;
  for (const auto& [sink, attached] : sinks_) needs = needs | attached.needs;
  return needs;
}

absl::Status SceneRunner::AttachDevice(FrameSink* sink, const std::string& tool, EffectSet needs) {
  std::lock_guard io(io_mu_);
  if (stopping_) return absl::UnavailableError("the scene is stopping");
  {
    std::lock_guard scene(scene_mu_);
    if (FindTool(loaded_, tool) < 0) {
      return absl::NotFoundError(absl::StrCat("no tool '", tool, "' in the scene"));
    }
  }
  for (const auto& [other, attached] : sinks_) {
    if (attached.tool == tool) {
      return absl::FailedPreconditionError(
          absl::StrCat("tool '", tool, "' is held by another device"));
    }
  }
  sinks_[sink] = Attached{tool, needs};
  return absl::OkStatus();
}

absl::Status SceneRunner::AttachViewer(FrameSink* sink, EffectSet needs) {
  std::lock_guard io(io_mu_);
  if (stopping_) return absl::UnavailableError("the scene is stopping");
  sinks_[sink] = Attached{"", needs};
  return absl::OkStatus();
}

void SceneRunner::Detach(FrameSink* sink) {
  {
    std::lock_guard io(io_mu_);
    sinks_.erase(sink);
    // The device that went may have been the only one not to have sent.
    if (DevicesFreshLocked()) {
      {
        std::lock_guard lock(stop_mu_);
        devices_fresh_ = true;
      }
      stop_cv_.notify_all();
    }
  }
  // An offer to `sink` that started before the erase ends before this.
  std::lock_guard offering(offer_mu_);
}

void SceneRunner::SetDevicePose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp) {
  std::lock_guard io(io_mu_);
  const auto it = sinks_.find(sink);
  if (it == sinks_.end() || it->second.tool.empty()) return;
  pending_[it->second.tool] = PendingPose{X_WD, stamp, true};
  if (DevicesFreshLocked()) {
    {
      std::lock_guard lock(stop_mu_);
      devices_fresh_ = true;
    }
    stop_cv_.notify_all();
  }
}

haptics::v1::SceneSpec SceneRunner::spec() const {
  std::lock_guard lock(scene_mu_);
  return spec_;
}

absl::Status SceneRunner::Replace(haptics::v1::SceneSpec spec, LoadedScene scene) {
  std::lock_guard io(io_mu_);
  for (const auto& [sink, attached] : sinks_) {
    if (!attached.tool.empty() && FindTool(scene, attached.tool) < 0) {
      return absl::FailedPreconditionError(
          absl::StrCat("tool '", attached.tool, "' is held by a device"));
    }
  }
  std::lock_guard lock(scene_mu_);
  // Tools keep where their devices put them; the proxies start over there.
  for (auto it = applied_.begin(); it != applied_.end();) {
    const ObjectId id = FindTool(scene, it->first);
    if (id < 0 || !scene.scene->SetDevicePose(id, it->second.X_WD).ok()) {
      it = applied_.erase(it);
    } else {
      ++it;
    }
  }
  // The old scene goes with `scene` once the locks are released: tearing
  // down its meshes and threads must not hold up the steps.
  std::swap(spec_, spec);
  std::swap(loaded_, scene);
  names_ = std::make_shared<const std::vector<std::string>>(loaded_.names);
  last_stats_ = StageStatsTable{};
  ++revision_;
  return absl::OkStatus();
}

RunnerInfo SceneRunner::Info() const {
  RunnerInfo info;
  std::lock_guard io(io_mu_);
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool.empty()) {
      ++info.viewers;
    } else {
      ++info.devices;
      info.claimed_tools.push_back(attached.tool);
    }
  }
  std::lock_guard lock(scene_mu_);
  info.spec = spec_;
  info.step = step_;
  info.triangles = loaded_.triangles;
  info.revision = revision_;
  return info;
}

}  // namespace hs
