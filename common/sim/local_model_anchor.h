#pragma once
// A tool's local model carried along with its proxy: while a touching
// proxy slides within a fraction of the validity radius, the planes of the
// last model built still hold (they stand for every face within its radius
// of the proxy it was taken at), and only what moved with the proxy needs
// saying anew: where the proxy and the device are now, the point the tool
// touches (the torque's lever), and the radius left. So a device's loop
// gets the server's proxy at each move, to correct its drift, without a
// face search or a plane test.

#include "common/sim/local_model.h"
#include "common/sim/proxy.h"

namespace hs {

/// Fills `out` with `built` (a model as BuildLocalModel makes it, taken at
/// its own proxy pose) anchored at `proxy`, whose pose has since translated
/// by t without turning (exactly), moved toward the device at `p_WD`: the same
/// half-spaces (each plane's gap grows by its normal times t, its points
/// move with the tool), the validity radius less |t| (a sphere of that
/// radius about the new proxy lies within the model's), only the planes
/// within it, nearest first; the touch from `proxy`; the revision left as
/// it was. False, with `out` unchanged, when the proxy turned, moved as far
/// as the radius, or lies behind a plane by more than rounding: it crossed
/// the plane of a face it has left (on a convex edge), so that the faces
/// near it are not the ones the planes were taken for; build a new model.
/// `behind_m`: how far behind a plane the tool may lie and still rest on it
/// (PlaneTouchTolerance). Allocates nothing once `out.planes` holds
/// `built`'s.
bool AnchorLocalModel(const LocalModel& built, const ProxyState& proxy, const Vector3d& p_WD,
                      double behind_m, LocalModel& out);

}  // namespace hs
