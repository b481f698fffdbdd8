#pragma once
// Test helper: an HDS object with its collision model and pose, ready for
// ComputeContact.

#include <memory>

#include "common/contact/contact_query.h"

namespace hs::testing_bodies {

struct Body {
  HapticObject object;
  CollisionModel model;
  Isometry3d X_WO = Isometry3d::Identity();

  PosedObject posed() const { return {&object, &model, X_WO}; }
};

/// A body of `object` (e.g. an imported model) at X_WO, hierarchy grown by
/// 1e-6 of its box diagonal (room for query tolerances up to 1e-6 relative).
inline std::unique_ptr<Body> MakeBody(HapticObject object,
                                      const Isometry3d& X_WO = Isometry3d::Identity(),
                                      BvType bv = BvType::kObbRss) {
  const double margin = 1e-6 * object.bounding_box().diagonal().norm();
  CollisionModel model(object, bv, margin);
  return std::make_unique<Body>(Body{std::move(object), std::move(model), X_WO});
}

/// A body of `mesh`, as above.
inline std::unique_ptr<Body> MakeBody(MeshInput mesh,
                                      const Isometry3d& X_WO = Isometry3d::Identity(),
                                      BvType bv = BvType::kObbRss) {
  return MakeBody(*HapticObject::Create("body", std::move(mesh)), X_WO, bv);
}

/// A square pyramid with its apex (vertex 0) at the origin and its base at
/// z = 1.
inline MeshInput ApexDownPyramid() {
  MeshInput mesh;
  mesh.materials.emplace_back();
  mesh.positions = {{0, 0, 0}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  mesh.faces = {{{0, 2, 1}}, {{0, 3, 2}}, {{0, 4, 3}}, {{0, 1, 4}}, {{1, 2, 3}}, {{1, 3, 4}}};
  return mesh;
}

inline Isometry3d Translation(double x, double y, double z) {
  Isometry3d X = Isometry3d::Identity();
  X.translation() = Vector3d(x, y, z);
  return X;
}

}  // namespace hs::testing_bodies
