#include "client/haptic_loop/model_request.h"

namespace hs {

ModelRequest ModelRequester::ForPose(double t_s, const Vector3d& p_W,
                                     int64_t beyond_validity_ticks) {
  sizer_.AddDevicePosition(t_s, p_W);
  const ModelRequest request{.model_stale = beyond_validity_ticks > beyond_validity_sent_,
                             .validity_radius_m = sizer_.WantedRadius()};
  beyond_validity_sent_ = beyond_validity_ticks;
  return request;
}

}  // namespace hs
