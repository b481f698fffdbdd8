#pragma once
// What a Device's two sides hand each other through triple buffers
// (triple_buffer.h): the device's newest pose to the network thread, and
// the stream's state and newest local model to the device's loop.

#include <chrono>
#include <cstdint>

#include "common/sim/local_model.h"
#include "haptics/pose.h"

namespace hs::sdk {

/// The steady clock, nanoseconds: a pose's time and a frame's arrival.
inline int64_t SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// Written by Tick, read by the network thread.
struct PoseSample {
  double position_m[3] = {0, 0, 0};
  double orientation_wxyz[4] = {1, 0, 0, 0};
  /// The steady clock at the tick, nanoseconds; 0: no pose yet.
  int64_t time_ns = 0;
  /// The loop's ticks past the validity sphere so far: when it grew since
  /// the last pose sent, the next says the model is stale.
  int64_t beyond_validity_ticks = 0;

  /// The sample of the device at `pose`, ticked at `time`.
  void Set(const haptics::Pose& pose, int64_t time, int64_t beyond_validity) {
    for (int i = 0; i < 3; ++i) position_m[i] = pose.position_m[i];
    for (int i = 0; i < 4; ++i) orientation_wxyz[i] = pose.orientation_wxyz[i];
    time_ns = time;
    beyond_validity_ticks = beyond_validity;
  }
};

/// Written by the network thread, read by Tick.
struct Feed {
  /// The stream it comes from: 1 for the first, +1 per reconnection.
  uint64_t stream = 0;
  bool connected = false;
  /// +1 per model taken from any stream; 0: none yet.
  uint64_t model_serial = 0;
  /// The stream's newest model; meaningful when model_serial is not 0 and
  /// came on this stream.
  LocalModel model;
  uint64_t model_stream = 0;
  /// The tool's force in the newest frame, world frame, newtons: what a
  /// device without the local model applies (DeviceOptions::local_model).
  double force_n[3] = {0, 0, 0};
};

}  // namespace hs::sdk
