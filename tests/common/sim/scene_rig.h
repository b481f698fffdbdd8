#pragma once
// Test helper: the floor-and-probe scene of the scene tests and the device
// path they drive it along.

#include <memory>
#include <vector>

#include "common/model/procedural.h"
#include "common/sim/scene.h"
#include "tests/common/sim/at_pose.h"

namespace hs {

// A 1 m x 1 m x 0.1 m floor with its top at z = 0, and a 2 cm cube probe
// whose bottom starts at z = 0.01.
struct Rig {
  std::unique_ptr<Scene> scene;
  ObjectId floor = -1, probe = -1;
};

inline Rig MakeRig(const SceneOptions& options = {}, double floor_thickness = 0.1) {
  Rig rig;
  rig.scene = *Scene::Create(options);
  rig.floor = *rig.scene->AddObject(
      *HapticObject::Create("floor", MakeBox(Vector3d(1, 1, floor_thickness))), ObjectKind::kFixed,
      At(0, 0, -floor_thickness / 2));
  rig.probe =
      *rig.scene->AddObject(*HapticObject::Create("probe", MakeBox(Vector3d::Constant(0.02))),
                            ObjectKind::kTool, At(0.1, 0.05, 0.02));
  return rig;
}

// The device path of the tests: 20 steps pressing 1 mm per step, from 1 cm
// above the floor to 1 cm into it, then 10 steps sliding 5 mm per step along x.
inline std::vector<Isometry3d> PressAndSlide() {
  std::vector<Isometry3d> path;
  for (int i = 1; i <= 20; ++i) path.push_back(At(0.1, 0.05, 0.02 - 0.001 * i));
  for (int i = 1; i <= 10; ++i) path.push_back(At(0.1 + 0.005 * i, 0.05, 0.0));
  return path;
}

// A 2 cm cube of 8 g (1000 kg/m^3) whose bottom starts `height` above the
// floor of MakeRig, free.
inline ObjectId AddCube(Scene& scene, double height, double x = 0.3, const BodyOptions& body = {}) {
  return *scene.AddObject(*HapticObject::Create("cube", MakeBox(Vector3d::Constant(0.02))),
                          ObjectKind::kFree, At(x, 0.05, 0.01 + height), body);
}

}  // namespace hs
