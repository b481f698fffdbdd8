#pragma once
// Internal to common/collision: the oriented-box overlap test of the pair
// traversal, lean enough for a 1 kHz loop. FCL's own (obbDisjoint) is out
// of line in the shared library and multiplies two 3x3 matrices per call;
// here each of B's boxes is mapped into A's frame once per query and kept,
// a bounding-sphere test rejects most pairs first, and the 15 axes of
// Gottschalk's separating axis test exit early.

#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/core/types.h"

namespace hs {

/// The oriented box that carries a volume's culling test: an OBB itself,
/// an OBBRSS's box. Volumes of other kinds have none (the overload set
/// tells them apart).
inline const fcl::OBBd& CullingBox(const fcl::OBBd& bv) { return bv; }
inline const fcl::OBBd& CullingBox(const fcl::OBBRSSd& bv) { return bv.obb; }

/// An oriented box in A's frame, with the radius of its bounding sphere.
struct PlacedBox {
  Matrix3d axis;  // columns: the box axes
  Vector3d center;
  Vector3d extent;  // half side lengths
  double radius = 0;
};

/// True when box `a` (A's frame) and `b` (already in A's frame) are
/// disjoint. Conservative: `kParallelSlack` keeps near-parallel edge axes
/// from rejecting what rounding makes look separated.
inline bool BoxesDisjoint(const fcl::OBBd& a, double a_radius, const PlacedBox& b) {
  constexpr double kParallelSlack = 1e-9;
  const double dx = b.center[0] - a.To[0], dy = b.center[1] - a.To[1], dz = b.center[2] - a.To[2];
  const double reach = a_radius + b.radius;
  if (dx * dx + dy * dy + dz * dz > reach * reach) return true;
  // Plain scalars: at -O2 Eigen's 3x3 expressions here cost several times
  // the arithmetic they express (callgrind).
  double R[3][3], abs_R[3][3], t[3];
  for (int i = 0; i < 3; ++i) {
    const double ax = a.axis(0, i), ay = a.axis(1, i), az = a.axis(2, i);
    t[i] = ax * dx + ay * dy + az * dz;
    for (int j = 0; j < 3; ++j) {
      R[i][j] = ax * b.axis(0, j) + ay * b.axis(1, j) + az * b.axis(2, j);
      abs_R[i][j] = std::abs(R[i][j]) + kParallelSlack;
    }
  }
  const double ea[3] = {a.extent[0], a.extent[1], a.extent[2]};
  const double eb[3] = {b.extent[0], b.extent[1], b.extent[2]};
  for (int i = 0; i < 3; ++i) {
    const double rb = eb[0] * abs_R[i][0] + eb[1] * abs_R[i][1] + eb[2] * abs_R[i][2];
    if (std::abs(t[i]) > ea[i] + rb) return true;
  }
  for (int j = 0; j < 3; ++j) {
    const double ra = ea[0] * abs_R[0][j] + ea[1] * abs_R[1][j] + ea[2] * abs_R[2][j];
    if (std::abs(t[0] * R[0][j] + t[1] * R[1][j] + t[2] * R[2][j]) > ra + eb[j]) return true;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * abs_R[i2][j] + ea[i2] * abs_R[i1][j];
      const double rb = eb[j1] * abs_R[i][j2] + eb[j2] * abs_R[i][j1];
      if (std::abs(t[i2] * R[i1][j] - t[i1] * R[i2][j]) > ra + rb) return true;
    }
  }
  return false;
}

/// B's boxes mapped into A's frame on first use within one query.
class PlacedBoxCache {
 public:
  /// Starts a query over `num_boxes` boxes of B with B-to-A map (R, T).
  void Start(int num_boxes, const Matrix3d& R, const Vector3d& T) {
    if (static_cast<int>(boxes_.size()) < num_boxes) {
      boxes_.resize(num_boxes);
      stamps_.resize(num_boxes, 0);
    }
    R_ = R;
    T_ = T;
    if (++stamp_ == 0) {  // wrapped: forget every stamp
      std::fill(stamps_.begin(), stamps_.end(), 0);
      stamp_ = 1;
    }
  }

  /// Box `j` of B (in B's frame) in A's frame.
  const PlacedBox& Get(int j, const fcl::OBBd& box_in_b) {
    PlacedBox& placed = boxes_[j];
    if (stamps_[j] != stamp_) {
      stamps_[j] = stamp_;
      placed.axis = R_ * box_in_b.axis;
      placed.center = R_ * box_in_b.To + T_;
      placed.extent = box_in_b.extent;
      placed.radius = box_in_b.extent.norm();
    }
    return placed;
  }

 private:
  std::vector<PlacedBox> boxes_;
  std::vector<uint32_t> stamps_;
  uint32_t stamp_ = 0;
  Matrix3d R_;
  Vector3d T_;
};

}  // namespace hs
