#pragma once
// The SDK Device's own parts, its loop (client/sdk/tick_renderer.h) and
// its protocol (client/sdk/device_protocol.h), on the caller's clock: a
// device whose one stream crosses a simulated link (delay_line.h) in
// simulated time, so that a closed-loop run against a Scene in process
// repeats exactly. What a haptics::Device does on its two threads, it
// does in turn at each tick.

#include <cstdint>

#include "client/remote/delay_line.h"
#include "client/sdk/device_config.h"
#include "client/sdk/device_protocol.h"
#include "client/sdk/tick_renderer.h"
#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

class SimulatedDevice {
 public:
  /// `config` outlives the device.
  SimulatedDevice(const sdk::DeviceConfig& config, const LinkConditions& link);

  /// Tick `k`, at k * options.tick_s: reads the frames the link delivers
  /// by then, renders for `pose` and, on the ticks of options.rate_hz
  /// (each tick at the tick rate or above), sends it.
  haptics::TickOutput Tick(int64_t k, const haptics::Pose& pose);

  /// Calls `send(request)` for each pose that reaches the server by
  /// `now_s`, in order.
  template <typename F>
  void DeliverPoses(double now_s, F&& send) {
    up_.PopDue(now_s, send);
  }
  /// A frame the server sent at `now_s`, onto the link back.
  void FromServer(double now_s, haptics::v1::Frame frame) { down_.Push(now_s, std::move(frame)); }

  sdk::LoopCounts counts() const { return renderer_.counts(); }
  LinkStats link_stats() const { return StatsOf(up_, down_); }

 private:
  const sdk::DeviceConfig& config_;
  sdk::DeviceProtocol protocol_;
  sdk::TickRenderer renderer_;
  DelayLine<haptics::v1::InteractRequest> up_;
  DelayLine<haptics::v1::Frame> down_;
  int64_t pose_period_ticks_ = 1;
};

}  // namespace hs::cli
