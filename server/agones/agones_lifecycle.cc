#include "server/agones/agones_lifecycle.h"

namespace hs {
namespace {

std::chrono::steady_clock::duration Seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}

}  // namespace

AgonesLifecycle::AgonesLifecycle(const AgonesOptions& options,
                                 std::function<ServerActivity()> activity, Metrics& metrics,
                                 std::ostream& log)
    : options_(options),
      activity_(std::move(activity)),
      metrics_(metrics),
      log_(log),
      sdk_(options.sdk_port),
      thread_([this] { Run(); }) {}

AgonesLifecycle::~AgonesLifecycle() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void AgonesLifecycle::Run() {
  log_ << "haptic-server: Agones SDK at 127.0.0.1:" << options_.sdk_port << std::endl;
  std::unique_lock lock(mu_);
  while (!stop_) {
    lock.unlock();
    Poll(Clock::now());
    lock.lock();
    cv_.wait_for(lock, Seconds(options_.poll_s), [this] { return stop_; });
  }
}

void AgonesLifecycle::Poll(Clock::time_point now) {
  if (now >= next_health_) {
    next_health_ = now + Seconds(options_.health_interval_s);
    Answered("health", sdk_.Health(), now);
  }
  if (now < retry_at_) return;
  const ServerActivity activity = activity_();
  if (!ready_) {
    ready_ = Answered("ready", sdk_.Ready(), now);
    if (!ready_) return;
  }
  const std::string label = AgonesLabelValue(activity.scene);
  if (!label.empty() && label != label_ && Answered("label", sdk_.SetLabel("scene", label), now)) {
    label_ = label;
  }
  if (activity.devices_joined > 0 && !allocated_) {
    allocated_ = Answered("allocate", sdk_.Allocate(), now);
  }
  // A client attached now, or one that came and went since the last poll,
  // starts the idle time over.
  const int64_t joined = activity.devices_joined + activity.viewers_joined;
  if (activity.devices + activity.viewers > 0 || joined != clients_joined_) {
    clients_joined_ = joined;
    idle_since_.reset();
    return;
  }
  if (joined == 0 || shutdown_requested_) return;
  if (!idle_since_) idle_since_ = now;
  if (now - *idle_since_ >= Seconds(options_.idle_shutdown_s)) {
    shutdown_requested_ = Answered("shutdown", sdk_.Shutdown(), now);
  }
}

bool AgonesLifecycle::Answered(const char* call, const absl::Status& status,
                               Clock::time_point now) {
  metrics_.AddAgonesRequest(call, status.ok());
  const bool health = std::string_view(call) == "health";
  if (!status.ok()) {
    if (!health) retry_at_ = now + Seconds(1);
    if (!sdk_failing_) {
      log_ << "haptic-server: Agones SDK: " << status.message()
           << "; clients are served as usual, the request is retried" << std::endl;
    }
    sdk_failing_ = true;
    return false;
  }
  if (sdk_failing_) log_ << "haptic-server: Agones SDK answers again" << std::endl;
  sdk_failing_ = false;
  if (!health) log_ << "haptic-server: Agones SDK: " << call << std::endl;
  return true;
}

}  // namespace hs
