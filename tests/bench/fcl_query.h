#pragma once
// FCL's exhaustive collide between a Table 1 case's two meshes
// (tests/common/contact/table1_cases.h): the baseline contact_bench times
// our queries against, and the yardstick step_bench divides its step times
// by, so that figures from a slower or busier machine still compare.

#include <fcl/fcl.h>

#include "tests/common/contact/table1_cases.h"

namespace hs {

class FclQuery {
 public:
  /// `enable_contact`: with contact points (FCL's contact query) or pairs
  /// only. The case must outlive the query (it holds FCL's hierarchies).
  FclQuery(const table1::Case& c, bool enable_contact);

  /// Places the moving object at X_WO for the next queries.
  void SetMovingPose(const Isometry3d& X_WO);

  /// One query into a fresh result, as FCL users query: clearing a kept one
  /// would keep its vector's capacity and hide its growth, which is part of
  /// FCL's cost.
  fcl::CollisionResultd Run() const;

 private:
  fcl::CollisionObjectd moving_;
  fcl::CollisionObjectd fixed_;
  fcl::CollisionRequestd request_;
};

}  // namespace hs
