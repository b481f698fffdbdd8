#pragma once
// Which planes of a tool's local model separate the tool from the plane's
// whole object, near the tool: the object lies behind the plane and the
// tool in front of it. In front of such a plane the tool meets nothing of
// that object, so a device may let the tool go wherever it is in front of
// any one of them (over a convex crest, down the far side), where every
// plane alone would hold it on the crest's planes extended past their
// faces (docs/remote-haptics.md, Separating planes).

#include <span>
#include <vector>

#include "common/contact/contact_query.h"
#include "common/sim/local_model.h"
#include "common/sim/step_frame.h"

namespace hs {

/// What MarkSeparatingPlanes found for a tool's last model, kept for its
/// next: most of a model's planes are the last one's, and their answers
/// are taken again rather than walked for anew (the same answers: a plane
/// is taken again only when everything its answer depends on is the
/// same).
class SeparationMemo {
 public:
  struct Entry {
    const void* model = nullptr;         ///< The object's hierarchy, and its
    uint64_t geometry_version = 0;       ///< geometry version,
    Isometry3d X_WO;                     ///< and pose.
    const void* tool_model = nullptr;    ///< The tool's hierarchy,
    uint64_t tool_geometry_version = 0;  ///< its geometry version
    Matrix3d R_WT;                       ///< and orientation.
    Vector3d normal_W;
    double offset = 0;       ///< normal . point on the plane
    double tool_height = 0;  ///< normal . (tool point - tool origin)
    AlignedBox3d region_W;   ///< Where the object's corners were checked.
    bool separating = false;
  };
  std::vector<Entry> entries, next;
};

/// Sets each plane's `separating` of `model` (taken with the tool `tool`
/// posed at the model's proxy pose; its planes name objects by id, as
/// `ids` names `obstacles`): true when no corner of the plane's object
/// near where the tool can reach lies in front of the plane, nor any
/// corner of the tool behind it through the plane's tool point, each by
/// more than rounding. Where the tool can reach: the tool's box at the
/// proxy grown by the validity radius, and then out to a grid of the
/// radius (so that the region, and the answer, stay the same over a
/// proxy's small moves and `memo` serves them). The same holds for the
/// tool moved by any translation within the radius, so for the model
/// anchored at a proxy within its sphere. Allocates nothing once `memo`
/// has held a model's planes.
void MarkSeparatingPlanes(const PosedObject& tool, std::span<const PosedObject> obstacles,
                          std::span<const ObjectId> ids, SeparationMemo& memo, LocalModel& model);

}  // namespace hs
