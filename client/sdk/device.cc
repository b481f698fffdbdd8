#include "haptics/device.h"

#include "client/sdk/device_impl.h"

namespace haptics {

Device::Impl::Impl(std::shared_ptr<grpc::Channel> channel, hs::sdk::DeviceConfig config)
    : renderer_(config.options), link_(std::move(channel), std::move(config), poses_, feeds_) {}

TickOutput Device::Impl::Tick(const Pose& pose) {
  feeds_.Take();
  const TickOutput out = renderer_.Tick(pose, feeds_.front());
  if (out.ok()) {
    hs::sdk::PoseSample& sample = poses_.back();
    sample.Set(pose, hs::sdk::SteadyNowNs(), renderer_.beyond_validity_ticks());
    poses_.Publish();
  }
  const hs::sdk::LoopCounts counts = renderer_.counts();
  beyond_validity_ticks_.store(counts.beyond_validity_ticks, std::memory_order_relaxed);
  rejected_poses_.store(counts.rejected_poses, std::memory_order_relaxed);
  models_rejected_.store(counts.models_rejected, std::memory_order_relaxed);
  models_restarted_.store(counts.models_restarted, std::memory_order_relaxed);
  passivity_ticks_.store(counts.passivity_ticks, std::memory_order_relaxed);
  passivity_dissipated_j_.store(counts.passivity_dissipated_j, std::memory_order_relaxed);
  return out;
}

DeviceState Device::Impl::State() const {
  DeviceState state = link_.State();
  state.beyond_validity_ticks = beyond_validity_ticks_.load(std::memory_order_relaxed);
  state.rejected_poses = rejected_poses_.load(std::memory_order_relaxed);
  state.models_rejected += models_rejected_.load(std::memory_order_relaxed);
  state.models_restarted = models_restarted_.load(std::memory_order_relaxed);
  state.passivity_ticks = passivity_ticks_.load(std::memory_order_relaxed);
  state.passivity_dissipated_j = passivity_dissipated_j_.load(std::memory_order_relaxed);
  return state;
}

Device::Device(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Device::~Device() = default;

TickOutput Device::Tick(const Pose& pose) { return impl_->Tick(pose); }

DeviceState Device::State() const { return impl_->State(); }

}  // namespace haptics

namespace hs::sdk {

haptics::Result<std::unique_ptr<haptics::Device>> OpenDevice(std::shared_ptr<grpc::Channel> channel,
                                                             DeviceConfig config) {
  auto impl = std::make_unique<haptics::Device::Impl>(std::move(channel), std::move(config));
  if (haptics::Error error = impl->Start(); !error.ok()) return error;
  return std::make_unique<haptics::Device>(std::move(impl));
}

}  // namespace hs::sdk
