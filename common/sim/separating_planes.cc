#include "common/sim/separating_planes.h"

#include <algorithm>
#include <cmath>

#include "common/collision/faces_in_box.h"
#include "common/sim/motion_bounds.h"

namespace hs {
namespace {

// How far in front of (or behind) its plane a corner may lie and count as
// on it, relative to the larger of the two objects' boxes: rounding.
constexpr double kSlackFraction = 1e-9;
// How near two planes' offsets and tool heights may be and still be the
// same plane for the memo, relative to the slack: their last bits.
constexpr double kRoundingFraction = 1e-3;
// The grid the checked region is grown out to, relative to the radius:
// a proxy's moves cross it once a radius or so (a coarser grid, fewer
// walks, each over more of the object).
constexpr double kGridFraction = 1.0;

// `box` grown by `by` and out to the grid of side `cell`.
AlignedBox3d OnGrid(const AlignedBox3d& box, double by, double cell) {
  AlignedBox3d out;
  for (int i = 0; i < 3; ++i) {
    out.min()[i] = std::floor((box.min()[i] - by) / cell) * cell;
    out.max()[i] = std::ceil((box.max()[i] + by) / cell) * cell;
  }
  return out;
}

// Whether `a`'s answer is `b`'s: the same object, pose, geometry, region
// and tool orientation, and the same plane and tool height within
// `rounding` (metres; planes the same pair gives at poses a shift apart
// differ in their last bits, and a corner that near the slack is
// rounding either way).
bool SameKey(const SeparationMemo::Entry& a, const SeparationMemo::Entry& b, double rounding) {
  return a.model == b.model && a.geometry_version == b.geometry_version &&
         a.tool_model == b.tool_model && a.tool_geometry_version == b.tool_geometry_version &&
         (a.normal_W - b.normal_W).lpNorm<Eigen::Infinity>() <= 1e-12 &&
         std::abs(a.offset - b.offset) <= rounding &&
         std::abs(a.tool_height - b.tool_height) <= rounding &&
         a.region_W.min() == b.region_W.min() && a.region_W.max() == b.region_W.max() &&
         a.R_WT == b.R_WT && a.X_WO.matrix() == b.X_WO.matrix();
}

}  // namespace

void MarkSeparatingPlanes(const PosedObject& tool, std::span<const PosedObject> obstacles,
                          std::span<const ObjectId> ids, SeparationMemo& memo, LocalModel& model) {
  const AlignedBox3d tool_box = WorldBox(*tool.object, tool.X_WO);
  const double r = model.validity_radius_m;
  for (ConstraintPlane& plane : model.planes) plane.separating = false;
  // Nothing is said of a model whose reach is not a number.
  if (!(std::isfinite(r) && r > 0) || !tool_box.sizes().allFinite()) return;
  const AlignedBox3d region = OnGrid(tool_box, r, kGridFraction * r);
  memo.next.clear();
  for (ConstraintPlane& plane : model.planes) {
    const auto k = std::find(ids.begin(), ids.end(), plane.object) - ids.begin();
    if (k == static_cast<long>(ids.size())) continue;
    const PosedObject& object = obstacles[k];
    const double slack = kSlackFraction * std::max(tool_box.diagonal().norm(),
                                                   object.object->bounding_box().diagonal().norm());
    // The model's own points first: another plane's point of this object
    // in front of this one (a higher corner under a flat tool face), or
    // its tool point behind, says no at once. Most planes end here.
    const bool beaten =
        std::any_of(model.planes.begin(), model.planes.end(), [&](const ConstraintPlane& other) {
          return other.object == plane.object &&
                 (plane.normal_W.dot(other.point_W - plane.point_W) > slack ||
                  plane.normal_W.dot(other.tool_point_W - plane.tool_point_W) < -slack);
        });
    if (beaten) continue;
    SeparationMemo::Entry entry{
        .model = object.model,
        .geometry_version = object.model->geometry_version(),
        .X_WO = object.X_WO,
        .tool_model = tool.model,
        .tool_geometry_version = tool.model->geometry_version(),
        .R_WT = tool.X_WO.linear(),
        .normal_W = plane.normal_W,
        .offset = plane.normal_W.dot(plane.point_W),
        .tool_height = plane.normal_W.dot(plane.tool_point_W - tool.X_WO.translation()),
        .region_W = region};
    const auto known = std::find_if(memo.entries.begin(), memo.entries.end(), [&](const auto& e) {
      return SameKey(e, entry, kRoundingFraction * slack);
    });
    entry.separating = known != memo.entries.end()
                           ? known->separating
                           : !AnyCornerInFront(*tool.model, tool.X_WO, tool_box, plane.tool_point_W,
                                               -plane.normal_W, slack) &&
                                 !AnyCornerInFront(*object.model, object.X_WO, region,
                                                   plane.point_W, plane.normal_W, slack);
    plane.separating = entry.separating;
    memo.next.push_back(entry);
  }
  std::swap(memo.entries, memo.next);
}

}  // namespace hs
