#include "common/sim/local_model_anchor.h"

#include <algorithm>

#include "common/sim/local_model_builder.h"

namespace hs {

bool AnchorLocalModel(const LocalModel& built, const ProxyState& proxy, const Vector3d& p_WD,
                      double behind_m, LocalModel& out) {
  if (proxy.X_WP.linear() != built.X_WP.linear()) return false;
  const Vector3d t = proxy.X_WP.translation() - built.X_WP.translation();
  const double radius_m = built.validity_radius_m - t.norm();
  if (!(radius_m > 0)) return false;
  for (const ConstraintPlane& plane : built.planes) {
    if (plane.gap_m + plane.normal_W.dot(t) < -behind_m) return false;
  }
  SetModelProxy(proxy, p_WD, out);
  out.validity_radius_m = radius_m;
  out.force_clamp_n = built.force_clamp_n;
  out.friction = built.friction;
  out.surface = built.surface;
  out.planes.clear();
  for (const ConstraintPlane& plane : built.planes) {
    const double along = plane.normal_W.dot(t);
    const double gap_m = std::max(plane.gap_m + along, 0.0);
    if (gap_m > radius_m) continue;
    ConstraintPlane& moved = out.planes.emplace_back(plane);
    moved.gap_m = gap_m;
    moved.tool_point_W = plane.tool_point_W + t;
    // The point of the plane nearest the moved tool point: moved with it
    // along the plane.
    moved.point_W = plane.point_W + (t - along * plane.normal_W);
  }
  // At most max_planes: sorting them allocates nothing.
  std::sort(out.planes.begin(), out.planes.end(), NearerPlane);
  return true;
}

}  // namespace hs
