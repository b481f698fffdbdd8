#pragma once
// What each pose of a remote device asks of the server's local model: a
// fresh one if the device's loop went past its model's validity sphere
// since the last pose (ToolPose.model_stale), and the validity radius it
// wants (ToolPose.validity_radius_m), sized from the round trips and the
// device's speed (validity_sizer.h). The SDK's device link and the
// operator runs of `hapticctl drive` stamp their poses with it. Eigen
// only, nothing allocated.

#include <cstdint>

#include "client/haptic_loop/validity_sizer.h"

namespace hs {

struct ModelRequest {
  bool model_stale = false;
  double validity_radius_m = 0;
};

class ModelRequester {
 public:
  explicit ModelRequester(const ValiditySizerOptions& options = {}) : sizer_(options) {}

  /// A frame applying a pose sent `round_trip_s` ago arrived at `t_s`.
  void AddRoundTrip(double t_s, double round_trip_s) { sizer_.AddRoundTrip(t_s, round_trip_s); }

  /// The request of a pose with the device at `p_W` going at `t_s`, the
  /// loop having counted `beyond_validity_ticks` ticks past its sphere so
  /// far (HapticLoop::beyond_validity_ticks).
  ModelRequest ForPose(double t_s, const Vector3d& p_W, int64_t beyond_validity_ticks);

 private:
  ValiditySizer sizer_;
  // The loop's count when the last pose went.
  int64_t beyond_validity_sent_ = 0;
};

}  // namespace hs
