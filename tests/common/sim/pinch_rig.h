#pragma once
// Test helper: two jaws (tools "left" and "right") either side of a free
// cube resting on the floor of MakeRig, driven to pinch it and lift it.

#include <gtest/gtest.h>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"
#include "tests/common/sim/scene_rig.h"

namespace hs {

struct PinchRig {
  Rig rig;
  ObjectId cube = -1, left = -1, right = -1;
  /// The jaws' centres' height at rest, metres.
  double jaw_z = 0.016;
  /// The last step's frame (null before the first).
  const StepFrame* frame = nullptr;

  /// Moves the left jaw `left_in` and the right one `right_in` towards the
  /// cube and both `up` from where they started, and steps.
  const StepFrame& DriveEach(double left_in, double right_in, double up) {
    EXPECT_TRUE(rig.scene->SetDevicePose(left, At(0.27 + left_in, 0.05, jaw_z + up)).ok());
    EXPECT_TRUE(rig.scene->SetDevicePose(right, At(0.33 - right_in, 0.05, jaw_z + up)).ok());
    frame = &rig.scene->Step();
    return *frame;
  }

  /// Moves both jaws `in` towards the cube and `up`, and steps.
  const StepFrame& Drive(double in, double up) { return DriveEach(in, in, up); }

  /// Closes the jaws' faces 2 mm into the cube (12 steps), then lifts them
  /// at 5 cm/s for 1 cm (200 steps).
  const StepFrame& PinchAndLift() {
    for (int i = 1; i <= 12; ++i) Drive(0.001 * i, 0);
    for (int i = 1; i <= 200; ++i) Drive(0.012, 0.00005 * i);
    return *frame;
  }
};

/// The rig's floor and probe (which stays home), the cube resting at
/// x = 0.3 after 50 steps, and jaws 2 cm thick, 3 cm wide and tall (no face
/// of theirs coplanar with one of the cube's), of friction `tool_friction`,
/// 1 cm either side of it, their centres at height `jaw_z` (by default
/// 1.6 cm: their bottoms 1 mm above the floor).
inline PinchRig MakePinchRig(double tool_friction, double jaw_z = 0.016) {
  PinchRig pinch{.rig = MakeRig(), .jaw_z = jaw_z};
  Scene& scene = *pinch.rig.scene;
  pinch.cube = AddCube(scene, 0);
  MeshInput jaw_mesh = MakeBox(Vector3d(0.02, 0.03, 0.03));
  for (Material& m : jaw_mesh.materials) m.static_friction = m.dynamic_friction = tool_friction;
  pinch.left = *scene.AddObject(*HapticObject::Create("left", jaw_mesh), ObjectKind::kTool,
                                At(0.27, 0.05, jaw_z));
  pinch.right = *scene.AddObject(*HapticObject::Create("right", jaw_mesh), ObjectKind::kTool,
                                 At(0.33, 0.05, jaw_z));
  for (int i = 0; i < 50; ++i) pinch.frame = &scene.Step();  // the cube settles
  return pinch;
}

}  // namespace hs
