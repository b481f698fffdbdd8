#pragma once
// A Device's two sides and what joins them: the device's loop
// (TickRenderer) and the network thread (DeviceLink), through two triple
// buffers.

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <memory>

#include "client/sdk/device_config.h"
#include "client/sdk/device_feed.h"
#include "client/sdk/device_link.h"
#include "client/sdk/tick_renderer.h"
#include "client/sdk/triple_buffer.h"
#include "haptics/device.h"

namespace haptics {

// Hidden: the Device class is exported, its state is not.
class [[gnu::visibility("hidden")]] Device::Impl {
 public:
  Impl(std::shared_ptr<grpc::Channel> channel, hs::sdk::DeviceConfig config);

  Error Start() { return link_.Start(); }
  TickOutput Tick(const Pose& pose);
  DeviceState State() const;

 private:
  hs::sdk::TripleBuffer<hs::sdk::PoseSample> poses_;
  hs::sdk::TripleBuffer<hs::sdk::Feed> feeds_;
  hs::sdk::TickRenderer renderer_;
  // The loop's counts, for State from other threads.
  std::atomic<int64_t> beyond_validity_ticks_{0};
  std::atomic<int64_t> rejected_poses_{0};
  std::atomic<int64_t> models_rejected_{0};
  std::atomic<int64_t> models_restarted_{0};
  std::atomic<int64_t> passivity_ticks_{0};
  std::atomic<double> passivity_dissipated_j_{0};
  // Last: its thread stops before the buffers go.
  hs::sdk::DeviceLink link_;
};

}  // namespace haptics

namespace hs::sdk {

/// A device on config.tool, once its stream's first frame came; else why not.
haptics::Result<std::unique_ptr<haptics::Device>> OpenDevice(std::shared_ptr<grpc::Channel> channel,
                                                             DeviceConfig config);

}  // namespace hs::sdk
