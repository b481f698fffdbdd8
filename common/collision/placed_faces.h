#pragma once
// Internal to common/collision: the faces of one object seen in the frame of
// a pair query, for the leaf buckets of the pair traversal. Each face is
// mapped (and its axis-aligned box in the query frame taken) on first use
// within a query, so a query touching few faces of a large mesh pays for
// those only, and one touching a face from many buckets maps it once.

#include <fcl/geometry/bvh/BVH_internal.h>
#include <fcl/math/triangle.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "common/collision/triangle_sat.h"
#include "common/core/types.h"

namespace hs {

/// A face in the query frame with its axis-aligned box.
struct PlacedFace {
  Triangle3d triangle;
  Vector3d normal;  // TriangleNormal(triangle)
  Vector3d lo, hi;  // box corners
};

/// True when the boxes of `a` and `b` are farther apart than `margin` along
/// some axis of the query frame.
inline bool FaceBoxesApart(const PlacedFace& a, const PlacedFace& b, double margin) {
  return a.lo[0] > b.hi[0] + margin || b.lo[0] > a.hi[0] + margin ||  //
         a.lo[1] > b.hi[1] + margin || b.lo[1] > a.hi[1] + margin ||  //
         a.lo[2] > b.hi[2] + margin || b.lo[2] > a.hi[2] + margin;
}

class PlacedFaces {
 public:
  /// Starts a query over the faces `triangles` (indices into `vertices`,
  /// object frame) mapped into the query frame by X. With a `sweep`
  /// (query frame), each box also holds the face moved by -sweep.
  void Start(const fcl::Vector3d* vertices, const fcl::Triangle* triangles, int num_faces,
             const Isometry3d& X, const Vector3d* sweep) {
    if (static_cast<int>(faces_.size()) < num_faces) {
      faces_.resize(num_faces);
      stamps_.resize(num_faces, 0);
    }
    vertices_ = vertices;
    triangles_ = triangles;
    R_ = X.linear();
    T_ = X.translation();
    sweep_ = sweep ? *sweep : Vector3d::Zero();
    if (++stamp_ == 0) {  // wrapped: forget every stamp
      std::fill(stamps_.begin(), stamps_.end(), 0);
      stamp_ = 1;
    }
  }

  /// Face `f` in the query frame.
  const PlacedFace& Get(int f) {
    PlacedFace& placed = faces_[f];
    if (stamps_[f] != stamp_) {
      stamps_[f] = stamp_;
      const fcl::Triangle& t = triangles_[f];
      for (int k = 0; k < 3; ++k) placed.triangle[k] = R_ * vertices_[t[k]] + T_;
      placed.normal = TriangleNormal(placed.triangle);
      placed.lo = placed.triangle[0].cwiseMin(placed.triangle[1]).cwiseMin(placed.triangle[2]);
      placed.hi = placed.triangle[0].cwiseMax(placed.triangle[1]).cwiseMax(placed.triangle[2]);
      placed.lo = placed.lo.cwiseMin(placed.lo - sweep_);
      placed.hi = placed.hi.cwiseMax(placed.hi - sweep_);
    }
    return placed;
  }

 private:
  std::vector<PlacedFace> faces_;
  std::vector<uint32_t> stamps_;
  uint32_t stamp_ = 0;
  const fcl::Vector3d* vertices_ = nullptr;
  const fcl::Triangle* triangles_ = nullptr;
  Matrix3d R_ = Matrix3d::Identity();
  Vector3d T_ = Vector3d::Zero();
  Vector3d sweep_ = Vector3d::Zero();
};

}  // namespace hs
