#include "tests/bench/accuracy_shapes.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <random>

#include "common/model/import.h"
#include "common/model/procedural.h"
#include "tests/bench/subdivided_model.h"
#include "tests/common/test_data_dir.h"

namespace hs::accuracy {
namespace {

// z_min over a mesh's vertices turned by R.
double LowestVertexZ(const HapticObject& object, const Matrix3d& R) {
  double z = std::numeric_limits<double>::infinity();
  for (const Vector3d& p : object.positions()) z = std::min(z, R.row(2).dot(p));
  return z;
}

const HapticObject& KidneyObject(int level) {
  static std::map<int, HapticObject> imported;
  auto it = imported.find(level);
  if (it != imported.end()) return it->second;
  const std::string base = hs::TestDataDir() + "/kidney.obj";
  std::string path = base;
  if (level > 0) {
    path =
        (std::filesystem::temp_directory_path() /
         ("hs_accuracy_kidney_" + std::to_string(getpid()) + "_" + std::to_string(level) + ".obj"))
            .string();
    const absl::Status written = WriteSubdividedObj(base, level, path);
    if (!written.ok()) {
      std::cerr << written << '\n';
      std::abort();
    }
  }
  absl::StatusOr<ImportedModel> model = ImportModel(path);
  if (level > 0) std::filesystem::remove(path);
  if (!model.ok()) {
    std::cerr << model.status() << '\n';
    std::abort();
  }
  return imported.emplace(level, std::move(model->object)).first->second;
}

}  // namespace

std::unique_ptr<Body> Slab(BvType bv) {
  return testing_bodies::MakeBody(MakeBox(Vector3d(1, 1, 0.2)),
                                  testing_bodies::Translation(0, 0, -0.1), bv);
}

Shape Sphere(int subdivisions) {
  constexpr double r = 0.02;
  return {"sphere", *HapticObject::Create("sphere", MakeIcosphere(r, subdivisions)),
          Matrix3d::Identity(), [](const Matrix3d&) { return -r; }, true};
}

Shape Torus(int major_segments) {
  constexpr double R = 0.04, r = 0.01, tilt = 0.3;
  return {"torus",
          *HapticObject::Create("torus", MakeTorus(R, r, major_segments, major_segments / 2)),
          Eigen::AngleAxisd(tilt, Vector3d::UnitX()).toRotationMatrix(),
          [](const Matrix3d&) { return -(R * std::sin(tilt) + r); }, false};
}

Shape Box() {
  static const HapticObject box = *HapticObject::Create("box", MakeBox(Vector3d::Constant(0.02)));
  return {"box", box, Matrix3d::Identity(), [](const Matrix3d& R) { return LowestVertexZ(box, R); },
          true};
}

Shape Kidney(int level) {
  return {"kidney",
          KidneyObject(level),
          Matrix3d::Identity(),
          [](const Matrix3d& R) { return LowestVertexZ(KidneyObject(kKidneyLevels - 1), R); },
          true,
          level == kKidneyLevels - 1};
}

std::vector<Config> Configs(const Shape& shape) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Config> configs;
  while (configs.size() < 16) {
    const Vector3d D = Vector3d(u(rng), u(rng), u(rng)).normalized();
    if (D.z() > -0.3) continue;                             // into the slab, not grazing
    const double press = 0.001 + 0.004 * (u(rng) + 1) / 2;  // 1 to 5 mm
    Isometry3d X = Isometry3d::Identity();
    X.linear() = shape.R_WO;
    if (shape.any_orientation) {
      X.linear() = Eigen::AngleAxisd(M_PI * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized())
                       .toRotationMatrix();
    }
    X.translation() = Vector3d(0.1 * u(rng), 0.1 * u(rng), -shape.lowest_z(X.linear()) - press);
    configs.push_back({X, D, press / -D.z()});
  }
  return configs;
}

}  // namespace hs::accuracy
