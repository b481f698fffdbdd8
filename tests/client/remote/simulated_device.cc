#include "simulated_device.h"

#include <cmath>

namespace hs::cli {

namespace pb = haptics::v1;

SimulatedDevice::SimulatedDevice(const sdk::DeviceConfig& config, const LinkConditions& link)
    : config_(config), protocol_(config), renderer_(config.options), up_(link, 0), down_(link, 1) {
  const haptics::DeviceOptions& o = config.options;
  if (o.rate_hz * o.tick_s < 1) pose_period_ticks_ = std::llround(1 / (o.rate_hz * o.tick_s));
  protocol_.Begin(1);
}

haptics::TickOutput SimulatedDevice::Tick(int64_t k, const haptics::Pose& pose) {
  const double now_s = static_cast<double>(k) * config_.options.tick_s;
  const int64_t now_ns = std::llround(now_s * 1e9);
  down_.PopDue(now_s, [&](const pb::Frame& frame) { protocol_.Read(frame, now_ns); });
  const haptics::TickOutput out = renderer_.Tick(pose, protocol_.feed());
  if (k % pose_period_ticks_ == 0 && out.ok()) {
    // Device times start at 1 ns: 0 is no pose.
    sdk::PoseSample sample;
    sample.Set(pose, now_ns + 1, renderer_.beyond_validity_ticks());
    pb::InteractRequest request;
    protocol_.PoseRequest(sample, request);
    up_.Push(now_s, std::move(request));
  }
  return out;
}

}  // namespace hs::cli
