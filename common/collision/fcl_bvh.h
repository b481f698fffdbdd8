#pragma once
// Internal to common/collision: the FCL side of CollisionModel. No header
// outside common/collision includes this one.

// BVH_model.h uses fit() without including it: keep this block first.
#include <fcl/math/bv/utility.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kIOS.h>

#include <array>
#include <cstdint>
#include <memory>
#include <variant>
#include <vector>

#include "common/collision/bucket_boxes.h"
#include "common/collision/collision_model.h"
#include "common/collision/placed_faces.h"
#include "common/collision/triangle_sat.h"

namespace hs {

template <typename BV>
using BvhPtr = std::shared_ptr<fcl::BVHModel<BV>>;

/// One hierarchy of whichever bounding volume the model was built with.
using AnyBvh = std::variant<BvhPtr<fcl::OBBRSSd>, BvhPtr<fcl::OBBd>, BvhPtr<fcl::RSSd>,
                            BvhPtr<fcl::kIOSd>, BvhPtr<fcl::AABBd>>;

struct CollisionModel::Impl {
  BvType type = BvType::kObbRss;
  /// Unique among the models this process has made: what a PairCache
  /// knows a model by (an address may be reused by a later model).
  uint64_t id = 0;
  double margin_m = 0;
  uint64_t geometry_version = 0;
  /// The centre of the object's box (object frame) and the largest distance
  /// of a vertex from it: how far a turn can move the object's points.
  Vector3d centre = Vector3d::Zero();
  double radius = 0;
  /// Per face: its corners' largest distance from `centre`, how far a turn
  /// can move that face (at most `radius`).
  std::vector<double> face_reach;
  AnyBvh bvh;
  /// Per face: zero area, so skipped by the leaf test (a flat triangle has
  /// no normal and SAT cannot separate it reliably; in a closed mesh its
  /// neighbours carry the contact). Bytes, not bits: read per face in the
  /// leaf buckets.
  std::vector<uint8_t> degenerate;
  /// Faces in the order of the hierarchy's leaves: node n holds faces
  /// leaf_faces[n.first_primitive, n.first_primitive + n.num_primitives).
  std::vector<int> leaf_faces;
  /// Face leaf_faces[i] in the object frame, placed for the leaf buckets.
  std::vector<PlacedFace> leaf_order_faces;
  /// Their boxes coordinate by coordinate, for a bucket's scan in lanes:
  /// lo[d][i], hi[d][i]; a degenerate face's box is empty, so never met.
  /// BoxColumns::kReadPast empty boxes follow the last face's.
  std::array<std::vector<double>, 3> leaf_order_lo, leaf_order_hi;
  /// Per node of the hierarchy (FCL's numbering): the box of its faces'
  /// boxes above, exactly their least and greatest coordinates (empty
  /// when all are degenerate). A pair query's leaf buckets start from it.
  std::vector<AxisBox> node_face_box;

  /// The hierarchy as FCL's generic geometry, for the broad phase.
  std::shared_ptr<fcl::CollisionGeometryd> geometry() const;
  /// Triangle `f` in the object frame.
  Triangle3d triangle(int f) const;
};

/// Grows a volume by `m` metres: it then bounds everything within `m` of
/// what it bounded.
inline void GrowVolume(fcl::OBBd& bv, double m) { bv.extent.array() += m; }
inline void GrowVolume(fcl::RSSd& bv, double m) { bv.r += m; }
inline void GrowVolume(fcl::OBBRSSd& bv, double m) {
  GrowVolume(bv.obb, m);
  GrowVolume(bv.rss, m);
}
inline void GrowVolume(fcl::kIOSd& bv, double m) {
  for (unsigned i = 0; i < bv.num_spheres; ++i) bv.spheres[i].r += m;
  GrowVolume(bv.obb, m);
}
inline void GrowVolume(fcl::AABBd& bv, double m) {
  bv.min_.array() -= m;
  bv.max_.array() += m;
}

}  // namespace hs
