#include "common/sim/proxy.h"

#include <utility>

#include "common/core/scratch.h"
#include "common/core/status_macros.h"
#include "common/sim/proxy_slide.h"
#include "common/sim/touched_face.h"

namespace hs {
namespace {

// Touches kept from step to step (common/core/scratch.h): each obstacle's,
// and the earliest of a slide.
struct ObstacleTouch {
  FirstTouch touch;
};
struct SlideTouch {
  FirstTouch touch;
};

// The earliest touch of the tool (orientation R) moving from p to p + v,
// into `earliest` (kept storage); returns the obstacle touched, -1 for none.
absl::StatusOr<int> FindEarliestTouch(const PosedObject& tool, const Matrix3d& R, const Vector3d& p,
                                      const Vector3d& v, std::span<const PosedObject> obstacles,
                                      const ProxyOptions& options, FirstTouch& earliest) {
  Isometry3d X_end = Isometry3d::Identity();
  X_end.linear() = R;
  X_end.translation() = p + v;
  // A buffer for each obstacle's touch, swapped with the earliest so far:
  // no allocation once both are large enough.
  FirstTouch& touch = Scratch<ObstacleTouch>().touch;
  int obstacle = -1;
  for (int i = 0; i < static_cast<int>(obstacles.size()); ++i) {
    HS_ASSIGN_OR_RETURN(const bool touched,
                        FindFirstTouch({tool.object, tool.model, X_end}, obstacles[i], v,
                                       options.relative_tolerance, touch));
    if (touched && (obstacle < 0 || touch.time < earliest.time)) {
      std::swap(earliest, touch);
      obstacle = i;
    }
  }
  return obstacle;
}

}  // namespace

absl::StatusOr<ProxyState> MoveProxy(const PosedObject& tool, const Isometry3d& X_WP_before,
                                     const Isometry3d& X_WD, std::span<const PosedObject> obstacles,
                                     const ProxyOptions& options) {
  // The proxy stops this far off a touched surface so that sliding along it
  // does not touch it again at once; far below what a hand can feel.
  const double stand_off = 1e-6 * tool.object->bounding_box().diagonal().norm();
  const Matrix3d R = X_WD.linear();
  const Vector3d device = X_WD.translation();
  Vector3d p = X_WP_before.translation();
  Vector3d goal = device;
  ProxyState state;
  FirstTouch& touch = Scratch<SlideTouch>().touch;  // the earliest touch of a slide
  for (int slide = 0; slide <= options.max_slides; ++slide) {
    const Vector3d v = goal - p;
    if (v.norm() <= stand_off * 1e-3) break;
    HS_ASSIGN_OR_RETURN(const int obstacle,
                        FindEarliestTouch(tool, R, p, v, obstacles, options, touch));
    if (obstacle < 0) {
      p = goal;
      break;
    }
    const Vector3d& n = touch.normal_W;
    p += touch.time * v + stand_off * n;
    const HapticObject& object = *obstacles[obstacle].object;
    state.touching = true;
    state.obstacle = obstacle;
    state.face = TouchedFace(object, touch.fixed);
    state.normal_W = n;
    state.p_WC = touch.points.empty() ? p : touch.points.front().p_WC;
    state.tool_face =
        touch.points.empty() ? 0 : FeatureFace(*tool.object, touch.points.front().moving);
    // Slide toward the device (proxy_slide.h), with the touched face's
    // friction when enabled.
    std::optional<SlideFriction> friction;
    if (options.friction) {
      const Material& m = object.face_material(state.face);
      friction = SlideFriction{m.static_friction, m.dynamic_friction};
    }
    const std::optional<Vector3d> next = SlideGoal(p, device, n, friction);
    if (!next) break;
    goal = *next;
  }
  state.X_WP.linear() = R;
  state.X_WP.translation() = p;
  return state;
}

}  // namespace hs
