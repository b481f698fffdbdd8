#pragma once
// Internal to common/contact: where two objects touch and with which
// features, found geometrically at a pose where they touch without
// penetrating. Works for any method that found the reversing distance.

#include <span>
#include <vector>

#include "common/contact/contact_context.h"
#include "common/contact/contact_set_f.h"

namespace hs {

struct LocatedContacts {
  /// Points in F's frame, one per distinct (moving feature, fixed feature).
  std::vector<ContactPointF> points;
  SideContact moving;
  SideContact fixed;
  /// Unit normal in F's frame from F toward M: the mean of the points'
  /// surface normals, each turned against the motion; -direction when none.
  Vector3d normal_F = Vector3d::Zero();
};

/// Locates the contacts of M posed at `X_FM` (F's frame) with F over the
/// face `pairs` (a: M's face, b: F's face) found at that pose. A corner of
/// one face within the tolerance of the other face is a vertex contact; two
/// edges within the tolerance at interior points are an edge-edge contact.
/// The feature of the other object holding a point is its vertex if within
/// the tolerance of one, else its edge if within the tolerance of one, else
/// its face. An edge that only splits one polygon of the source model
/// (the diagonal of a triangulated quad) counts as the face: it is no edge
/// of the shape. Writes `out` over, keeping its vectors' storage.
void LocateContacts(const ContactContext& context, const Isometry3d& X_FM,
                    std::span<const TrianglePair> pairs, LocatedContacts& out);

}  // namespace hs
