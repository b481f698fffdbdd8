#pragma once
// The face whose material a contact feels.

#include "common/contact/contact_set.h"
#include "common/hds/haptic_object.h"

namespace hs {

/// A face of `object` that holds `feature` (the face itself, else the
/// first face of the edge or vertex; 0 for none).
inline FaceId FeatureFace(const HapticObject& object, const Feature& feature) {
  switch (feature.kind) {
    case FeatureKind::kFace:
      return feature.id;
    case FeatureKind::kEdge:
      return object.EdgeFaces(feature.id).front();
    case FeatureKind::kVertex:
      return object.VertexFaces(feature.id).front();
    case FeatureKind::kNone:
      break;
  }
  return 0;
}

/// A face of `object` that holds the contact `side` (its first face, else a
/// face of its first edge, else of its first vertex; 0 when it is empty).
inline FaceId TouchedFace(const HapticObject& object, const SideContact& side) {
  if (!side.faces.empty()) return side.faces.front();
  if (!side.edges.empty()) return FeatureFace(object, {FeatureKind::kEdge, side.edges.front()});
  if (!side.vertices.empty()) {
    return FeatureFace(object, {FeatureKind::kVertex, side.vertices.front()});
  }
  return 0;
}

/// The outward normal of a face-kind `side` of `object` posed at X_WO: the
/// normalized sum of its faces' unit normals, world frame; zero when the
/// side is not a face contact or the sum vanishes. For a face resting on or
/// pushed by a face, the contact set's own normal may be any separating
/// axis of the coincident pair; the face's normal is the one that pushes.
inline Vector3d FaceSideNormal(const HapticObject& object, const SideContact& side,
                               const Isometry3d& X_WO) {
  if (side.kind != FeatureKind::kFace) return Vector3d::Zero();
  Vector3d sum = Vector3d::Zero();
  for (const FaceId f : side.faces) {
    const auto& v = object.face(f).vertices;
    const Vector3d n = (object.position(v[1]) - object.position(v[0]))
                           .cross(object.position(v[2]) - object.position(v[0]));
    if (n.norm() > 0) sum += n.normalized();
  }
  const double length = sum.norm();
  return length > 1e-9 ? Vector3d(X_WO.linear() * sum / length) : Vector3d::Zero();
}

}  // namespace hs
