#pragma once
// A haptic device on one tool of a running scene. The device's own loop
// (typically 1 kHz, often a real-time thread) calls Tick with the pose it
// measured and applies the force returned; a network thread of the
// Device's own streams the poses to the server at DeviceOptions::rate_hz
// and takes the tool's local contact models from its frames. Tick renders
// the newest model (a god object on its planes, docs/remote-haptics.md) and
// never waits for the network: it takes no lock, allocates nothing and
// makes no system call but reading the steady clock.
//
// While the link is down (the server stopped, the network gone) Tick
// returns zero force without kConnected, the network thread reconnects
// with exponential back-off, and the device is seated again on its next
// pose: force resumes from the first model of the new stream.

#include <cstdint>
#include <memory>

#include "haptics/error.h"
#include "haptics/export.h"
#include "haptics/pose.h"

namespace haptics {

struct DeviceOptions {
  /// Poses sent per second.
  double rate_hz = 250;
  /// Frames asked for per second; 0: rate_hz.
  double frame_rate_hz = 0;
  /// Render from the local contact model (the default). false: Tick
  /// returns the force of the newest frame, as the server computed it for
  /// the last pose it applied; for a link of a few milliseconds only, since
  /// the force is a round trip old (docs/remote-haptics.md).
  bool local_model = true;
  /// The largest damping the loop's passivity controller adds, N*s/m; 0
  /// turns it off (docs/remote-haptics.md).
  double max_passivity_damping_ns_per_m = 30;
  /// The period the caller ticks at, seconds (the loop's velocity for the
  /// planes' dampers is taken over it).
  double tick_s = 1e-3;
  /// Take the tool from the device holding it (the admin role).
  bool take_over = false;
  /// Open gives up after this long without the stream's first frame,
  /// seconds; <= 0: the session's connect timeout.
  double open_timeout_s = 0;
  /// Back-off between reconnection attempts: the first wait, doubling up
  /// to the largest, seconds.
  double reconnect_initial_s = 0.05;
  double reconnect_max_s = 2;
};

/// TickOutput::flags.
enum TickFlag : uint32_t {
  /// The stream is up and the force comes from its newest model.
  kConnected = 1u << 0,
  /// A model has arrived on this stream (without one the force is zero).
  kHasModel = 1u << 1,
  /// The proxy touches a plane.
  kTouching = 1u << 2,
  /// The force was clamped to the scene's clamp.
  kClamped = 1u << 3,
  /// The device is past the model's validity sphere (only the touched
  /// plane's push is felt; the next pose asks the server for a new model).
  kBeyondValidity = 1u << 4,
};

enum class TickStatus : int {
  kOk = 0,
  /// A coordinate was not finite or the quaternion not unit (within 1e-6):
  /// the output holds the last force and the pose is not sent.
  kInvalidPose = 1,
};

struct TickOutput {
  /// On the device, world frame, newtons; torque about the device origin,
  /// newton metres.
  double force_n[3] = {0, 0, 0};
  double torque_nm[3] = {0, 0, 0};
  /// TickFlag bits.
  uint32_t flags = 0;
  TickStatus status = TickStatus::kOk;

  bool ok() const { return status == TickStatus::kOk; }
};

/// The device as its network thread sees it; any thread may ask.
struct DeviceState {
  bool connected = false;
  /// The last round trip: a pose's Tick to the frame that applied it,
  /// seconds; -1 before the first.
  double round_trip_s = -1;
  /// Since the newest model arrived, seconds; -1 before the first.
  double model_age_s = -1;
  /// Ticks past the model's validity sphere, since the device opened.
  int64_t beyond_validity_ticks = 0;
  /// Streams opened again after one ended.
  int64_t reconnects = 0;
  int64_t frames = 0;
  int64_t models = 0;
  int64_t rejected_poses = 0;
  /// Models that failed the checks (not rendered).
  int64_t models_rejected = 0;
  /// Models whose device pose was not among the loop's last ticks' (the
  /// proxy restarted at the server's).
  int64_t models_restarted = 0;
  /// Ticks the passivity controller damped, and the work it took back from
  /// the hand, joules.
  int64_t passivity_ticks = 0;
  double passivity_dissipated_j = 0;
  /// Why the last stream ended (kOk while the first is up). A stream that
  /// ends for good (taken over, a refused token) is not reopened: then
  /// `closed` is set.
  Error last_error;
  bool closed = false;
};

class HAPTICS_EXPORT Device {
 public:
  class Impl;
  explicit Device(std::unique_ptr<Impl> impl);
  /// Ends the stream and joins the network thread.
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  /// One tick of the device's loop with the device at `pose`: the force to
  /// apply. Wait-free; call it from one thread at a time.
  TickOutput Tick(const Pose& pose);

  DeviceState State() const;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace haptics
