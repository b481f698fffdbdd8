#include "tests/bench/fcl_query.h"

namespace hs {
namespace {

// Large enough that FCL never stops early: its exhaustive mode.
constexpr size_t kFclMaxContacts = 1 << 24;

}  // namespace

FclQuery::FclQuery(const table1::Case& c, bool enable_contact)
    : moving_(c.moving->fcl_bvh, c.moving->X_WO), fixed_(c.fixed->fcl_bvh, c.fixed->X_WO) {
  request_.num_max_contacts = kFclMaxContacts;
  request_.enable_contact = enable_contact;
}

void FclQuery::SetMovingPose(const Isometry3d& X_WO) {
  moving_.setTransform(X_WO);
  moving_.computeAABB();
}

fcl::CollisionResultd FclQuery::Run() const {
  fcl::CollisionResultd result;
  fcl::collide(&moving_, &fixed_, request_, result);
  return result;
}

}  // namespace hs
