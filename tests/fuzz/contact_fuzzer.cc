// libFuzzer target: the contact query on meshes and poses made of the
// input's bytes, non-finite numbers and degenerate triangles included, from
// scratch and through a pair cache.
// Bad input must come back as a status, never as a crash or a hang; and
// within the sizes a scene admits (vertices within 1e7 m of their object's
// origin, poses within 1e6 m of the world's), an answer is finite in every
// number it holds, or the fuzzer aborts.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
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

bool WithinAScene(const hs::HapticObject& object, const hs::Isometry3d& X_WO) {
  const hs::AlignedBox3d& box = object.bounding_box();
  return box.min().cwiseAbs().maxCoeff() <= 1e7 && box.max().cwiseAbs().maxCoeff() <= 1e7 &&
         X_WO.translation().cwiseAbs().maxCoeff() <= 1e6;
}

// Aborts when a query the scene sizes admit answered with a number that is
// not finite (plane depths are infinite when unset, and stay out of it).
void CheckFinite(const absl::Status& status, const hs::ContactSet& set,
                 const hs::PosedObject& moving, const hs::PosedObject& fixed) {
  if (!status.ok() || !WithinAScene(*moving.object, moving.X_WO) ||
      !WithinAScene(*fixed.object, fixed.X_WO)) {
    return;
  }
  bool finite = std::isfinite(set.depth_m) && set.direction_W.allFinite() &&
                set.reversing_vector_W.allFinite() && set.normal_W.allFinite() &&
                std::isfinite(set.tolerance_m) && std::isfinite(set.time_of_impact.value_or(0));
  for (const hs::ContactPoint& point : set.points) finite = finite && point.p_WC.allFinite();
  if (!finite) {
    std::fprintf(stderr,
                 "a contact set within a scene's sizes holds a number not finite: depth %g\n",
                 set.depth_m);
    std::abort();
  }
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
  hs::ContactSet set;
  CheckFinite(hs::ComputeContact(at_first, at_fixed, query, set), set, at_first, at_fixed);
  // Through a pair cache, at that pose and then at a second one: a region
  // built, then reused or replaced.
  hs::PairCache cache;
  CheckFinite(hs::ComputeContact(at_first, at_fixed, query, set, &cache), set, at_first, at_fixed);
  const hs::PosedObject at_second{moving.get(), &moving_model, Pose(in)};
  CheckFinite(hs::ComputeContact(at_second, at_fixed, query, set, &cache), set, at_second,
              at_fixed);
  return 0;
}
