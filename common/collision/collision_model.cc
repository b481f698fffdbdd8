#include "common/collision/collision_model.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <utility>

#include "common/collision/fcl_bvh.h"
#include "common/core/check.h"
#include "common/hds/triangle.h"

namespace hs {
namespace {

template <typename BV>
void GrowAll(fcl::BVHModel<BV>& model, double margin) {
  for (int i = 0; i < model.getNumBVs(); ++i) GrowVolume(model.getBV(i).bv, margin);
  model.computeLocalAABB();
  model.aabb_local.min_.array() -= margin;
  model.aabb_local.max_.array() += margin;
  model.aabb_radius += margin;
}

std::vector<fcl::Vector3d> Vertices(const HapticObject& object) {
  return std::vector<fcl::Vector3d>(object.positions().begin(), object.positions().end());
}

std::vector<uint8_t> DegenerateFaces(const HapticObject& object) {
  std::vector<uint8_t> degenerate(object.num_faces());
  for (FaceId f = 0; f < object.num_faces(); ++f) {
    const auto& v = object.face(f).vertices;
    degenerate[f] =
        IsDegenerateTriangle(object.position(v[0]), object.position(v[1]), object.position(v[2]));
  }
  return degenerate;
}

template <typename BV>
BvhPtr<BV> Build(const HapticObject& object, double margin) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(object.num_faces());
  for (const Face& f : object.faces()) {
    triangles.emplace_back(f.vertices[0], f.vertices[1], f.vertices[2]);
  }
  HS_CHECK(model->beginModel(object.num_faces(), object.num_vertices()) == fcl::BVH_OK);
  HS_CHECK(model->addSubModel(Vertices(object), triangles) == fcl::BVH_OK);
  HS_CHECK(model->endModel() == fcl::BVH_OK);
  GrowAll(*model, margin);
  return model;
}

AnyBvh BuildAny(const HapticObject& object, BvType type, double margin) {
  switch (type) {
    case BvType::kObbRss:
      return Build<fcl::OBBRSSd>(object, margin);
    case BvType::kObb:
      return Build<fcl::OBBd>(object, margin);
    case BvType::kRss:
      return Build<fcl::RSSd>(object, margin);
    case BvType::kKios:
      return Build<fcl::kIOSd>(object, margin);
    case BvType::kAabb:
      return Build<fcl::AABBd>(object, margin);
  }
  HS_CHECK(false);
}

// FCL keeps its own leaf order private; every leaf holds one face at its
// position in that order, so the leaves give it back.
std::vector<int> LeafFaces(const AnyBvh& bvh) {
  return std::visit(
      [](const auto& model) {
        std::vector<int> faces(model->num_tris, -1);
        for (int n = 0; n < model->getNumBVs(); ++n) {
          const auto& node = model->getBV(n);
          if (node.isLeaf()) faces[node.first_primitive] = node.primitiveId();
        }
        return faces;
      },
      bvh);
}

// The centre of the object's box, its vertices' largest distance from it,
// and each face's.
void PlaceCentre(const HapticObject& object, CollisionModel::Impl& impl) {
  impl.centre = object.bounding_box().center();
  impl.radius = 0;
  for (const Vector3d& p : object.positions()) {
    impl.radius = std::max(impl.radius, (p - impl.centre).norm());
  }
  impl.face_reach.assign(object.num_faces(), 0);
  for (int f = 0; f < object.num_faces(); ++f) {
    for (const VertexId v : object.face(f).vertices) {
      impl.face_reach[f] = std::max(impl.face_reach[f], (object.position(v) - impl.centre).norm());
    }
  }
}

// Places the faces in leaf order (leaf_order_faces) with their boxes, the
// box arrays followed by BoxColumns::kReadPast empty boxes (whole vectors
// are read past a bucket's last face).
void PlaceLeafOrderFaces(CollisionModel::Impl& impl) {
  const size_t n = impl.leaf_faces.size();
  impl.leaf_order_faces.clear();
  impl.leaf_order_faces.reserve(n);
  for (int d = 0; d < 3; ++d) {
    impl.leaf_order_lo[d].assign(n + BoxColumns::kReadPast,
                                 std::numeric_limits<double>::infinity());
    impl.leaf_order_hi[d].assign(n + BoxColumns::kReadPast,
                                 -std::numeric_limits<double>::infinity());
  }
  for (size_t i = 0; i < n; ++i) {
    const int f = impl.leaf_faces[i];
    const PlacedFace& face = impl.leaf_order_faces.emplace_back(PlaceFace(impl.triangle(f)));
    if (impl.degenerate[f]) continue;
    for (int d = 0; d < 3; ++d) {
      impl.leaf_order_lo[d][i] = face.lo[d];
      impl.leaf_order_hi[d][i] = face.hi[d];
    }
  }
}

// The box of each node's faces' boxes (node_face_box), from the leaves
// up: FCL numbers a node's children after it, so a reverse scan meets
// them first, and a node's box is its children's, min and max being exact.
void PlaceNodeFaceBoxes(CollisionModel::Impl& impl) {
  std::visit(
      [&impl](const auto& model) {
        const int n = model->getNumBVs();
        impl.node_face_box.resize(n);
        for (int k = n - 1; k >= 0; --k) {
          const auto& node = model->getBV(k);
          AxisBox& box = impl.node_face_box[k];
          box = AxisBox::Empty();
          if (node.isLeaf()) {
            for (int i = node.first_primitive; i < node.first_primitive + node.num_primitives;
                 ++i) {
              const double lo[3] = {impl.leaf_order_lo[0][i], impl.leaf_order_lo[1][i],
                                    impl.leaf_order_lo[2][i]};
              const double hi[3] = {impl.leaf_order_hi[0][i], impl.leaf_order_hi[1][i],
                                    impl.leaf_order_hi[2][i]};
              box.Include(lo, hi);
            }
            continue;
          }
          for (const int child : {node.leftChild(), node.rightChild()}) {
            HS_CHECK(child > k && child < n);
            box.Include(impl.node_face_box[child].lo, impl.node_face_box[child].hi);
          }
        }
      },
      impl.bvh);
}

}  // namespace

std::shared_ptr<fcl::CollisionGeometryd> CollisionModel::Impl::geometry() const {
  return std::visit([](const auto& m) -> std::shared_ptr<fcl::CollisionGeometryd> { return m; },
                    bvh);
}

Triangle3d CollisionModel::Impl::triangle(int f) const {
  return std::visit(
      [f](const auto& m) {
        const fcl::Triangle& t = m->tri_indices[f];
        return Triangle3d{m->vertices[t[0]], m->vertices[t[1]], m->vertices[t[2]]};
      },
      bvh);
}

CollisionModel::CollisionModel(const HapticObject& object, BvType type, double margin_m)
    : impl_(std::make_unique<Impl>()) {
  HS_CHECK(margin_m >= 0);
  static std::atomic<uint64_t> models_made{0};
  impl_->type = type;
  impl_->id = ++models_made;
  impl_->margin_m = margin_m;
  impl_->geometry_version = object.geometry_version();
  impl_->bvh = BuildAny(object, type, margin_m);
  PlaceCentre(object, *impl_);
  impl_->degenerate = DegenerateFaces(object);
  impl_->leaf_faces = LeafFaces(impl_->bvh);
  PlaceLeafOrderFaces(*impl_);
  PlaceNodeFaceBoxes(*impl_);
}

CollisionModel::~CollisionModel() = default;
CollisionModel::CollisionModel(CollisionModel&&) noexcept = default;
CollisionModel& CollisionModel::operator=(CollisionModel&&) noexcept = default;

BvType CollisionModel::bv_type() const { return impl_->type; }
double CollisionModel::margin_m() const { return impl_->margin_m; }
uint64_t CollisionModel::geometry_version() const { return impl_->geometry_version; }

bool CollisionModel::Sync(const HapticObject& object) {
  if (object.geometry_version() == impl_->geometry_version) return false;
  std::visit(
      [&](auto& model) {
        HS_CHECK(model->num_vertices == object.num_vertices());
        HS_CHECK(model->beginUpdateModel() == fcl::BVH_OK);
        HS_CHECK(model->updateSubModel(Vertices(object)) == fcl::BVH_OK);
        // Top-down: FCL 0.7's bottom-up refit merges RSS children into volumes
        // that miss triangles (triangle_pairs_test caught it); top-down fits
        // every node to its own triangles, O(n log n) instead of O(n).
        HS_CHECK(model->endUpdateModel(/*refit=*/true, /*bottomup=*/false) == fcl::BVH_OK);
        GrowAll(*model, impl_->margin_m);
      },
      impl_->bvh);
  impl_->degenerate = DegenerateFaces(object);
  PlaceCentre(object, *impl_);
  PlaceLeafOrderFaces(*impl_);
  PlaceNodeFaceBoxes(*impl_);
  impl_->geometry_version = object.geometry_version();
  return true;
}

}  // namespace hs
