#pragma once
// The accuracy sweep's shapes and poses: a sphere, a tilted torus, a box
// and an imported non-convex model (kidney.obj refined by Catmull-Clark), each
// pressed 1 to 5 mm into the flat top (z = 0) of a large slab along
// directions D drawn with a fixed seed.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tests/common/contact/contact_test_bodies.h"

namespace hs::accuracy {

using testing_bodies::Body;

/// A 1 m x 1 m x 0.2 m slab with its top face at z = 0; hierarchies grown
/// by 1e-6 of the box diagonal, as scenes build them.
std::unique_ptr<Body> Slab(BvType bv);

/// A mesh with the reference shape its depth is measured against.
struct Shape {
  std::string name;
  HapticObject object;
  /// Orientation in the world when not any_orientation.
  Matrix3d R_WO = Matrix3d::Identity();
  /// z_min of the reference shape turned by R, its origin at the world
  /// origin, metres.
  std::function<double(const Matrix3d& R)> lowest_z;
  /// The reference is measured in any orientation (a sphere, the imported
  /// model): each pose turns the mesh at random.
  bool any_orientation = false;
  /// The mesh is its own reference shape (the finest imported level): it
  /// has no depth error against it to report.
  bool is_reference = false;
};

/// An icosphere of 2 cm radius, 20 * 4^subdivisions faces; the reference is
/// the smooth sphere (analytic).
Shape Sphere(int subdivisions);

/// A 4 cm / 1 cm torus of m x m/2 quads (2 faces each) tilted by 0.3 rad
/// about x; the reference is the smooth torus, whose lowest point lies on no
/// vertex ring (analytic).
Shape Torus(int major_segments);

/// A 2 cm cube, turned at random each pose; its mesh is its exact shape,
/// so the reference is analytic: its lowest corner.
Shape Box();

/// Levels of the imported model: 0 is kidney.obj itself (128 faces), level
/// k > 0 its Catmull-Clark refinement, 128 * 6 * 4^(k-1) faces after the
/// importer triangulates its quads.
inline constexpr int kKidneyLevels = 6;

/// The imported model at `level`, read by ImportModel from a file (level 0:
/// tests/data/kidney.obj; others: that file refined by assimp and written to
/// a temporary OBJ). It has no analytic shape: its reference shape is the
/// finest level, whose lowest vertex each pose places `press` below z = 0.
/// Levels are imported once per run. Aborts when the file cannot be read.
Shape Kidney(int level);

/// One query: a pose of the shape and D.
struct Config {
  Isometry3d X_WO;
  Vector3d D;
  /// The reference shape's depth along D, metres.
  double depth;
};

/// 16 poses and directions (fixed seed): D at least 17 degrees off the
/// surface, the reference shape's lowest point 1 to 5 mm below z = 0.
std::vector<Config> Configs(const Shape& shape);

}  // namespace hs::accuracy
