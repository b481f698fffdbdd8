#include "server/stream_registry.h"

#include "absl/strings/str_cat.h"

namespace hs {

absl::Status StreamRegistry::AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                                          const std::function<bool(const std::string&)>& has_tool,
                                          const absl::Status* take_over, bool* displaced) {
  std::lock_guard lock(mu_);
  if (closed_) return absl::UnavailableError("the scene is stopping");
  if (!has_tool(claim.tool))
    return absl::NotFoundError(absl::StrCat("no tool '", claim.tool, "' in the scene"));
  for (auto it = sinks_.begin(); it != sinks_.end(); ++it) {
    if (it->second.tool != claim.tool) continue;
    if (take_over == nullptr) {
      return absl::FailedPreconditionError(
          absl::StrCat("tool '", claim.tool, "' is held by another device"));
    }
    EndDeviceLocked(it, *take_over);
    if (displaced != nullptr) *displaced = true;
    break;
  }
  sinks_[sink] = Attached{.tool = claim.tool,
                          .needs = claim.needs,
                          .holder = claim.holder,
                          .heard = std::chrono::steady_clock::now()};
  ++devices_joined_;
  UpdateHoldersLocked();
  return absl::OkStatus();
}

void StreamRegistry::EndDeviceLocked(std::map<FrameSink*, Attached>::iterator it,
                                     const absl::Status& status) {
  // Closed under the lock, as CloseAll does: its stream's end (Detach)
  // waits for it, so the sink is still there.
  it->first->Close(status);
  pending_.erase(it->second.tool);
  sinks_.erase(it);
}

void StreamRegistry::EndSilentDevices(std::chrono::steady_clock::time_point silent_since,
                                      const absl::Status& status,
                                      std::vector<std::string>& released) {
  std::lock_guard lock(mu_);
  const size_t before = released.size();
  for (auto it = sinks_.begin(); it != sinks_.end();) {
    const auto next = std::next(it);
    if (!it->second.tool.empty() && it->second.heard < silent_since) {
      released.push_back(it->second.tool);
      EndDeviceLocked(it, status);
    }
    it = next;
  }
  if (released.size() == before) return;
  UpdateHoldersLocked();
  // The devices left may all have sent.
  if (DevicesFreshLocked()) devices_fresh_(true);
}

void StreamRegistry::UpdateHoldersLocked() {
  auto holders = std::make_shared<ToolHolders>();
  for (const auto& [sink, attached] : sinks_) {
    if (!attached.tool.empty()) (*holders)[attached.tool] = attached.holder;
  }
  holders_ = std::move(holders);
}

absl::Status StreamRegistry::AttachViewer(FrameSink* sink, EffectSet needs) {
  std::lock_guard lock(mu_);
  if (closed_) return absl::UnavailableError("the scene is stopping");
  sinks_[sink] = Attached{.needs = needs};
  ++viewers_joined_;
  return absl::OkStatus();
}

std::optional<std::string> StreamRegistry::Detach(FrameSink* sink) {
  std::lock_guard lock(mu_);
  const auto it = sinks_.find(sink);
  if (it == sinks_.end()) return std::nullopt;
  std::string tool = std::move(it->second.tool);
  sinks_.erase(it);
  if (!tool.empty()) UpdateHoldersLocked();
  // The device that went may have been the only one not to have sent.
  if (DevicesFreshLocked()) devices_fresh_(true);
  return tool;
}

void StreamRegistry::SetPose(FrameSink* sink, const Isometry3d& X_WD, const AppliedPose& stamp) {
  std::lock_guard lock(mu_);
  const auto it = sinks_.find(sink);
  if (it == sinks_.end() || it->second.tool.empty()) return;
  PendingPose& pending = pending_[it->second.tool];
  // A first pose not taken yet stays a seat when a later one replaces it.
  const bool seat = !it->second.sent_pose || (pending.fresh && pending.seat);
  pending = PendingPose{X_WD, stamp, true, seat};
  it->second.sent_pose = true;
  it->second.heard = std::chrono::steady_clock::now();
  if (DevicesFreshLocked()) devices_fresh_(true);
}

EffectSet StreamRegistry::TakeFreshPoses(FreshPoses& fresh) {
  fresh.count = 0;
  std::lock_guard lock(mu_);
  for (auto& [tool, pose] : pending_) {
    if (!pose.fresh) continue;
    if (fresh.count == fresh.entries.size()) fresh.entries.emplace_back();
    fresh.entries[fresh.count].first = tool;  // keeps the string's storage
    fresh.entries[fresh.count].second = pose;
    ++fresh.count;
    pose.fresh = false;
  }
  fresh.holders = holders_;
  EffectSet needs;
  for (const auto& [sink, attached] : sinks_) needs = needs | attached.needs;
  devices_fresh_(false);
  return needs;
}

void StreamRegistry::ListSinks(std::vector<FrameSink*>& out) const {
  out.clear();
  std::lock_guard lock(mu_);
  for (const auto& [sink, attached] : sinks_) out.push_back(sink);
}

absl::Status StreamRegistry::WhileToolsHeld(const std::function<bool(const std::string&)>& has_tool,
                                            const std::function<void()>& then) {
  std::lock_guard lock(mu_);
  for (const auto& [sink, attached] : sinks_) {
    if (!attached.tool.empty() && !has_tool(attached.tool)) {
      return absl::FailedPreconditionError(
          absl::StrCat("tool '", attached.tool, "' is held by a device"));
    }
  }
  then();
  return absl::OkStatus();
}

void StreamRegistry::CloseAll(const absl::Status& status) {
  std::lock_guard lock(mu_);
  closed_ = true;
  for (auto& [sink, attached] : sinks_) sink->Close(status);
}

StreamRegistry::Counts StreamRegistry::counts() const {
  Counts counts;
  std::lock_guard lock(mu_);
  counts.devices_joined = devices_joined_;
  counts.viewers_joined = viewers_joined_;
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool.empty()) {
      ++counts.viewers;
    } else {
      ++counts.devices;
      counts.claimed_tools.push_back(attached.tool);
    }
  }
  return counts;
}

bool StreamRegistry::DevicesFreshLocked() const {
  bool any = false;
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool.empty()) continue;
    const auto it = pending_.find(attached.tool);
    if (it == pending_.end() || !it->second.fresh) return false;
    any = true;
  }
  return any;
}

}  // namespace hs
