#include "server/stream_registry.h"

#include "absl/strings/str_cat.h"
#include "common/core/check.h"

namespace hs {

ObjectId SceneTools::Find(const std::string& name) const {
  for (const auto& [tool_name, id] : tools) {
    if (tool_name == name) return id;
  }
  return -1;
}

StreamRegistry::StreamRegistry(SceneTools tools)
    : tools_(std::move(tools)),
      pending_(tools_.object_count),
      holders_(std::make_shared<const ToolHolders>(tools_.object_count)) {}

const std::string& StreamRegistry::ToolName(ObjectId tool) const {
  for (const auto& [name, id] : tools_.tools) {
    if (id == tool) return name;
  }
  HS_CHECK(false && "an attached device's tool is in the scene's tools");
  return tools_.tools.front().first;
}

absl::Status StreamRegistry::AttachDevice(FrameSink* sink, const DeviceClaim& claim,
                                          const absl::Status* take_over, bool* displaced) {
  std::lock_guard lock(mu_);
  if (closed_) return absl::UnavailableError("the scene is stopping");
  const ObjectId tool = tools_.Find(claim.tool);
  if (tool < 0) return absl::NotFoundError(absl::StrCat("no tool '", claim.tool, "' in the scene"));
  for (auto it = sinks_.begin(); it != sinks_.end(); ++it) {
    if (it->second.tool != tool) continue;
    if (take_over == nullptr) {
      return absl::FailedPreconditionError(
          absl::StrCat("tool '", claim.tool, "' is held by another device"));
    }
    EndDeviceLocked(it, *take_over);
    if (displaced != nullptr) *displaced = true;
    break;
  }
  sinks_[sink] = Attached{.tool = tool,
                          .needs = claim.needs,
                          .holder = claim.holder,
                          .heard = std::chrono::steady_clock::now()};
  ++devices_;
  ++devices_joined_;
  changes_.fetch_add(1, std::memory_order_release);
  UpdateHoldersLocked();
  return absl::OkStatus();
}

void StreamRegistry::DropPendingLocked(ObjectId tool) {
  PendingPose& pending = pending_[tool];
  if (pending.fresh) --devices_with_fresh_pose_;
  pending = PendingPose{};
}

void StreamRegistry::EndDeviceLocked(SinkMap::iterator it, const absl::Status& status) {
  ends_.push_back({it->first, status});
  changes_.fetch_add(1, std::memory_order_release);
  DropPendingLocked(it->second.tool);
  --devices_;
  sinks_.erase(it);
}

StreamChange StreamRegistry::EndSilentDevices(std::chrono::steady_clock::time_point silent_since,
                                              const absl::Status& status,
                                              std::vector<std::string>& released) {
  std::lock_guard lock(mu_);
  const size_t before = released.size();
  for (auto it = sinks_.begin(); it != sinks_.end();) {
    const auto next = std::next(it);
    if (it->second.tool >= 0 && it->second.heard < silent_since) {
      released.push_back(ToolName(it->second.tool));
      EndDeviceLocked(it, status);
    }
    it = next;
  }
  if (released.size() == before) return {};
  UpdateHoldersLocked();
  return {.tool = std::nullopt, .devices_fresh_since = DevicesFreshLocked()};
}

void StreamRegistry::UpdateHoldersLocked() {
  auto holders = std::make_shared<ToolHolders>(tools_.object_count);
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool >= 0) (*holders)[attached.tool] = {sink, attached.holder};
  }
  holders_ = std::move(holders);
}

absl::Status StreamRegistry::AttachViewer(FrameSink* sink, EffectSet needs) {
  std::lock_guard lock(mu_);
  if (closed_) return absl::UnavailableError("the scene is stopping");
  sinks_[sink] = Attached{.needs = needs};
  ++viewers_joined_;
  changes_.fetch_add(1, std::memory_order_release);
  return absl::OkStatus();
}

StreamChange StreamRegistry::Detach(FrameSink* sink) {
  std::lock_guard lock(mu_);
  std::erase_if(ends_, [sink](const SinkEnd& end) { return end.sink == sink; });
  const auto it = sinks_.find(sink);
  if (it == sinks_.end()) return {};
  const ObjectId tool = it->second.tool;
  sinks_.erase(it);
  if (tool < 0) return {.tool = "", .devices_fresh_since = std::nullopt};
  DropPendingLocked(tool);
  --devices_;
  UpdateHoldersLocked();
  // The device that went may have been the only one not to have sent.
  return {.tool = ToolName(tool), .devices_fresh_since = DevicesFreshLocked()};
}

StreamChange StreamRegistry::SetPose(FrameSink* sink, const Isometry3d& X_WD,
                                     const AppliedPose& stamp, const LocalModelRequest& model) {
  std::lock_guard lock(mu_);
  const auto it = sinks_.find(sink);
  if (it == sinks_.end() || it->second.tool < 0) return {};
  PendingPose& pending = pending_[it->second.tool];
  // A first pose not taken yet stays a seat when a later one replaces it.
  const bool seat = !it->second.sent_pose || (pending.fresh && pending.seat);
  if (!pending.fresh) ++devices_with_fresh_pose_;
  pending = PendingPose{.X_WD = X_WD,
                        .stamp = stamp,
                        .fresh = true,
                        .seat = seat,
                        .model = {.stale = model.stale || (pending.fresh && pending.model.stale),
                                  .validity_radius_m = model.validity_radius_m,
                                  .surface_only = model.surface_only}};
  it->second.sent_pose = true;
  it->second.heard = std::chrono::steady_clock::now();
  return {.tool = std::nullopt, .devices_fresh_since = DevicesFreshLocked()};
}

EffectSet StreamRegistry::TakeFreshPoses(FreshPoses& fresh) {
  fresh.count = 0;
  std::lock_guard lock(mu_);
  if (devices_with_fresh_pose_ > 0) {
    for (size_t tool = 0; tool < pending_.size(); ++tool) {
      PendingPose& pose = pending_[tool];
      if (!pose.fresh) continue;
      if (fresh.count == fresh.entries.size()) fresh.entries.emplace_back();
      fresh.entries[fresh.count++] = {static_cast<ObjectId>(tool), pose};
      pose.fresh = false;
    }
    devices_with_fresh_pose_ = 0;
  }
  fresh.holders = holders_;
  fresh.generation = ++takes_;
  EffectSet needs;
  for (const auto& [sink, attached] : sinks_) needs = needs | attached.needs;
  return needs;
}

void StreamRegistry::ListSinks(std::vector<FrameSink*>& out) const {
  out.clear();
  std::lock_guard lock(mu_);
  for (const auto& [sink, attached] : sinks_) out.push_back(sink);
}

void StreamRegistry::TakeEnds(std::vector<SinkEnd>& out) {
  out.clear();
  std::lock_guard lock(mu_);
  out.swap(ends_);
}

absl::Status StreamRegistry::RemapTools(SceneTools next) {
  std::lock_guard lock(mu_);
  std::vector<std::pair<Attached*, ObjectId>> moves;
  for (auto& [sink, attached] : sinks_) {
    if (attached.tool < 0) continue;
    const std::string& name = ToolName(attached.tool);
    const ObjectId id = next.Find(name);
    if (id < 0) {
      return absl::FailedPreconditionError(absl::StrCat("tool '", name, "' is held by a device"));
    }
    moves.emplace_back(&attached, id);
  }
  std::vector<PendingPose> pending(next.object_count);
  for (auto& [attached, id] : moves) {
    pending[id] = pending_[attached->tool];
    attached->tool = id;
  }
  pending_ = std::move(pending);
  tools_ = std::move(next);
  UpdateHoldersLocked();
  return absl::OkStatus();
}

void StreamRegistry::CloseAll(const absl::Status& status) {
  std::lock_guard lock(mu_);
  closed_ = true;
  for (const auto& [sink, attached] : sinks_) ends_.push_back({sink, status});
  changes_.fetch_add(1, std::memory_order_release);
}

StreamRegistry::Counts StreamRegistry::counts() const {
  Counts counts;
  std::lock_guard lock(mu_);
  counts.devices_joined = devices_joined_;
  counts.viewers_joined = viewers_joined_;
  for (const auto& [sink, attached] : sinks_) {
    if (attached.tool < 0) {
      ++counts.viewers;
    } else {
      ++counts.devices;
      counts.claimed_tools.push_back(ToolName(attached.tool));
    }
  }
  return counts;
}

std::optional<uint64_t> StreamRegistry::DevicesFreshLocked() const {
  if (devices_ == 0 || devices_with_fresh_pose_ < devices_) return std::nullopt;
  return takes_;
}

}  // namespace hs
