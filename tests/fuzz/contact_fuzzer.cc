// libFuzzer target: the contact query on meshes and poses made of the
// input's bytes, non-finite numbers and degenerate triangles included, from
// scratch and through a pair cache.
// Bad input must come back as a status, never as a crash or a hang.

#include <cstddef>
#include <cstdint>
#include <memory>

#include "common/collision/collision_model.h"
#include "common/contact/contact_query.h"
#include "tests/fuzz/fuzz_bytes.h"

namespace {

using hs::fuzz::Bytes;

// A mesh of up to 8 vertices and 8 faces over them, or nullptr when
// HapticObject refuses it (that refusal is the edge's check).
std::unique_ptr<hs::HapticObject> Mesh(Bytes& in) {
  hs::MeshInput mesh;
  mesh.materials.emplace_back();
  const int vertices = 3 + in.Small(6);
  for (int v = 0; v < vertices; ++v)
    mesh.positions.emplace_back(in.Number(), in.Number(), in.Number());
  const int faces = 1 + in.Small(8);
  for (int f = 0; f < faces; ++f) {
    mesh.faces.push_back(
        hs::FaceInput{.vertices = {in.Small(vertices), in.Small(vertices), in.Small(vertices)}});
  }
  absl::StatusOr<hs::HapticObject> object = hs::HapticObject::Create("m", std::move(mesh));
  if (!object.ok()) return nullptr;
  return std::make_unique<hs::HapticObject>(*std::move(object));
}

hs::Isometry3d Pose(Bytes& in) {
  hs::Isometry3d X = hs::Isometry3d::Identity();
  X.translation() = hs::Vector3d(in.Number(), in.Number(), in.Number());
  const hs::Vector3d axis(in.Number(), in.Number(), in.Number());
  if (axis.norm() > 0 && std::isfinite(axis.norm())) {
    X.linear() = Eigen::AngleAxisd(axis.norm(), axis.normalized()).toRotationMatrix();
  }
  return X;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  std::unique_ptr<hs::HapticObject> moving = Mesh(in);
  std::unique_ptr<hs::HapticObject> fixed = Mesh(in);
  if (moving == nullptr || fixed == nullptr) return 0;
  const hs::CollisionModel moving_model(*moving, hs::BvType::kObbRss, 1e-9);
  const hs::CollisionModel fixed_model(*fixed, hs::BvType::kObbRss, 1e-9);
  hs::ContactQuery query;
  query.direction_W = hs::Vector3d(in.Number(), in.Number(), in.Number());
  query.method = in.Small(2) == 0 ? hs::ContactMethod::kSweep3d : hs::ContactMethod::kPaper2d;
  const hs::PosedObject at_first{moving.get(), &moving_model, Pose(in)};
  const hs::PosedObject at_fixed{fixed.get(), &fixed_model, Pose(in)};
  (void)hs::ComputeContact(at_first, at_fixed, query);
  // Through a pair cache, at that pose and then at a second one: a region
  // built, then reused or replaced.
  hs::PairCache cache;
  hs::ContactSet set;
  (void)hs::ComputeContact(at_first, at_fixed, query, set, &cache);
  (void)hs::ComputeContact({moving.get(), &moving_model, Pose(in)}, at_fixed, query, set, &cache);
  return 0;
}
