#pragma once
// Internal to common/collision: faces with their normals and boxes, as the
// leaf buckets of the pair traversal test them. A pair query works in the
// frame of its first object A, whose faces are placed once, when its model
// is built (CollisionModel::Impl::leaf_order_faces); the second object's
// faces are mapped into A's frame on first use within a query, so a query
// touching few faces of a large mesh pays for those only, and one touching a
// face from many buckets maps it once.

#include <fcl/geometry/bvh/BVH_internal.h>
#include <fcl/math/triangle.h>

#include <algorithm>

#include "common/collision/triangle_sat.h"
#include "common/core/id_memo.h"
#include "common/core/types.h"

namespace hs {

/// A face in the query frame with its axis-aligned box.
struct PlacedFace {
  Triangle3d triangle;
  Vector3d normal;  // TriangleNormal(triangle)
  Vector3d lo, hi;  // box corners
};

inline PlacedFace PlaceFace(const Triangle3d& triangle) {
  PlacedFace placed{triangle, TriangleNormal(triangle), {}, {}};
  placed.lo = triangle[0].cwiseMin(triangle[1]).cwiseMin(triangle[2]);
  placed.hi = triangle[0].cwiseMax(triangle[1]).cwiseMax(triangle[2]);
  return placed;
}

/// True when every corner of `t` lies farther than `margin` on one side of
/// the plane of `face` while `t` moves by `shift` times the face normal's
/// length, for every fraction of the move in [0, 1] (0: no move): the swept
/// leaf test's first, cheap rejection.
inline bool BeyondFacePlane(const PlacedFace& face, const Triangle3d& t, double margin,
                            double shift) {
  const Vector3d& origin = face.triangle[0];
  const double d0 = face.normal.dot(t[0] - origin);
  const double d1 = face.normal.dot(t[1] - origin);
  const double d2 = face.normal.dot(t[2] - origin);
  const double slack = margin * face.normal.norm();
  const double lo = std::min(std::min(d0, d1), d2) + std::min(0.0, shift);
  const double hi = std::max(std::max(d0, d1), d2) + std::max(0.0, shift);
  return lo > slack || hi < -slack;
}

/// The faces of the second object of a pair query, in the first one's frame.
class PlacedFaces {
 public:
  /// Starts a query over the faces `triangles` (indices into `vertices`,
  /// object frame) mapped into the query frame by X.
  void Start(const fcl::Vector3d* vertices, int num_vertices, const fcl::Triangle* triangles,
             int num_faces, const Isometry3d& X) {
    faces_.Reset(num_faces);
    vertices_placed_.Reset(num_vertices);
    vertices_ = vertices;
    triangles_ = triangles;
    R_ = X.linear();
    T_ = X.translation();
  }

  /// The faces by id; face f is placed once Get(f) was called in this
  /// query.
  const PlacedFace* data() const { return faces_.data(); }

  /// Face `f` in the query frame. Inlined up to the test of whether it
  /// is placed: the pair query's candidate loop asks for a face of B per
  /// candidate, most of them placed already.
  [[gnu::always_inline]] const PlacedFace& Get(int f) {
    if (const PlacedFace* placed = faces_.Find(f)) return *placed;
    return Place(f);
  }

 private:
  [[gnu::noinline]] const PlacedFace& Place(int f) {
    return faces_.Get(f, [&] {
      const fcl::Triangle& t = triangles_[f];
      return PlaceFace({Vertex(t[0]), Vertex(t[1]), Vertex(t[2])});
    });
  }

  // Vertex `v` in the query frame: each once, for the faces around it.
  const Vector3d& Vertex(int v) {
    return vertices_placed_.Get(v, [&] { return Vector3d(R_ * vertices_[v] + T_); });
  }

  IdMemo<PlacedFace> faces_;
  IdMemo<Vector3d> vertices_placed_;
  const fcl::Vector3d* vertices_ = nullptr;
  const fcl::Triangle* triangles_ = nullptr;
  Matrix3d R_ = Matrix3d::Identity();
  Vector3d T_ = Vector3d::Zero();
};

}  // namespace hs
