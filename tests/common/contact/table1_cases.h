#pragma once
// Test and benchmark support: the four cases of the paper's Table 1 (its
// fig. 8, growing in size), each a moving and a fixed object with FCL's
// own hierarchy beside ours, and their coherent sequences: the moving
// object sliding and turning through the contact, one pose per haptic
// step. Used by tests/bench/contact_bench (timing) and by
// coherent_contact_test (the pair cache's answers).

#include <fcl/fcl.h>

#include <memory>
#include <string>
#include <vector>

#include "common/collision/collision_model.h"
#include "common/contact/contact_query.h"
#include "common/hds/haptic_object.h"

namespace hs::table1 {

using FclBvh = fcl::BVHModel<fcl::OBBRSSd>;

// ComputeContact's default; the pair query is timed at the same tolerance.
inline constexpr double kRelativeTolerance = 1e-9;

// One object: its HDS and hierarchy as ComputeContact sees them, and FCL's
// own hierarchy of the same triangles for the baselines.

struct Body {
  HapticObject object;
  CollisionModel model;
  Isometry3d X_WO;
  std::shared_ptr<FclBvh> fcl_bvh;

  PosedObject posed() const { return {&object, &model, X_WO}; }
};

struct PaperRow {
  int lines;
  int vertices;
  double seconds;
};

struct Case {
  std::string name;
  std::string description;
  PaperRow paper;
  std::unique_ptr<Body> moving;
  std::unique_ptr<Body> fixed;
  Vector3d direction_W;
};

inline constexpr int kNumCases = 4;

/// Case `index` (0-3: #1-#4), made on first use.
const Case& GetCase(int index);

/// The tolerance ComputeContact derives from the query: relative to the
/// pair's size, the sum of the two objects' box diagonals.
double ToleranceM(const Case& c);

/// The case's query along its approach direction.
ContactQuery Query(const Case& c, ContactMethod method);

// Coherent sequences: each case's moving object slides along world x at
// kSlideMps and turns about the world vertical through its own origin at
// kTurnRadPs, from the case's pose, for kCoherentSteps steps at 1 kHz: what
// a hand-held tool does between two haptic steps. The query's direction
// stays the case's approach direction (pressing down while sliding).

inline constexpr int kCoherentSteps = 1000;
inline constexpr double kCoherentStepS = 0.001;
inline constexpr double kSlideMps = 0.1;
inline constexpr double kTurnRadPs = 1.0;

/// Case `index`'s sequence of kCoherentSteps poses of the moving object.
const std::vector<Isometry3d>& CoherentPoses(int index);

}  // namespace hs::table1
