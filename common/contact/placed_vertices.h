#pragma once
// Internal to common/contact: an object's vertices placed by a pose, each
// once between resets however many faces ask for it (a vertex of a mesh is
// a corner of about six faces), with the same numbers as placing each
// face's corners (ContactContext::MovingTriangle).

#include "common/collision/triangle_sat.h"
#include "common/core/id_memo.h"
#include "common/hds/haptic_object.h"

namespace hs {

class PlacedVertices {
 public:
  /// Forgets every vertex placed; from now on `object`'s are placed by X.
  /// `object` must outlive the use until the next Reset.
  void Reset(const HapticObject& object, const Isometry3d& X) {
    object_ = &object;
    X_ = X;
    placed_.Reset(object.num_vertices());
  }

  /// Face `f`'s corners, placed.
  Triangle3d Face(FaceId f) {
    const TriangleCorners c = Corners(f);
    return {*c[0], *c[1], *c[2]};
  }

  /// Where face `f`'s placed corners are kept, until the next Reset.
  TriangleCorners Corners(FaceId f) {
    const auto& v = object_->face(f).vertices;
    return {&Vertex(v[0]), &Vertex(v[1]), &Vertex(v[2])};
  }

 private:
  const Vector3d& Vertex(VertexId v) {
    return placed_.Get(v, [&] { return Vector3d(X_ * object_->position(v)); });
  }

  const HapticObject* object_ = nullptr;
  Isometry3d X_ = Isometry3d::Identity();
  IdMemo<Vector3d> placed_;
};

}  // namespace hs
