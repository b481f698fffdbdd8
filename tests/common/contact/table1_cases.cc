#include "tests/common/contact/table1_cases.h"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "common/core/check.h"
#include "common/model/procedural.h"

namespace hs::table1 {
namespace {

// ----------------------------------------------------------------------------
// Meshes the procedural library does not have. Closed, counter-clockwise seen
// from outside (CheckOutward verifies it).

void AddTriangle(MeshInput& mesh, int a, int b, int c) {
  mesh.faces.push_back(FaceInput{{a, b, c}, 0, static_cast<PolygonId>(mesh.faces.size())});
}

// Cone with its apex (vertex 0) at the origin and its base, a regular
// `sides`-gon of `radius`, at z = `height`: an apex of valence `sides`.
MeshInput MakeCone(double radius, double height, int sides) {
  MeshInput mesh;
  mesh.materials.emplace_back();
  mesh.positions.emplace_back(0, 0, 0);
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    mesh.positions.emplace_back(radius * std::cos(a), radius * std::sin(a), height);
  }
  const int centre = sides + 1;
  mesh.positions.emplace_back(0, 0, height);
  for (int k = 0; k < sides; ++k) {
    const int p = 1 + k, q = 1 + (k + 1) % sides;
    AddTriangle(mesh, 0, q, p);
    AddTriangle(mesh, centre, p, q);
  }
  return mesh;
}

// Cylinder along x, centred at the origin, its side a `sides`-gon prism cut
// into `segments` slices along the axis, its ends fans around a centre
// vertex. Vertex (s, k) is at angle 2 pi k / sides from +y towards +z.
MeshInput MakeCylinder(double radius, double length, int sides, int segments) {
  MeshInput mesh;
  mesh.materials.emplace_back();
  for (int s = 0; s <= segments; ++s) {
    const double x = -length / 2 + length * s / segments;
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * std::numbers::pi * k / sides;
      mesh.positions.emplace_back(x, radius * std::cos(a), radius * std::sin(a));
    }
  }
  auto id = [&](int s, int k) { return s * sides + k % sides; };
  for (int s = 0; s < segments; ++s) {
    for (int k = 0; k < sides; ++k) {
      AddTriangle(mesh, id(s, k), id(s, k + 1), id(s + 1, k + 1));
      AddTriangle(mesh, id(s, k), id(s + 1, k + 1), id(s + 1, k));
    }
  }
  const int left = static_cast<int>(mesh.positions.size());
  mesh.positions.emplace_back(-length / 2, 0, 0);
  const int right = left + 1;
  mesh.positions.emplace_back(length / 2, 0, 0);
  for (int k = 0; k < sides; ++k) {
    AddTriangle(mesh, left, id(0, k + 1), id(0, k));
    AddTriangle(mesh, right, id(segments, k), id(segments, k + 1));
  }
  return mesh;
}

// A wrongly wound mesh would still collide, but inside/outside (colliding
// vertices) and the paper's penetration direction would be nonsense.
void CheckOutward(const MeshInput& mesh) {
  double six_volume = 0;
  for (const FaceInput& f : mesh.faces) {
    const auto& p = mesh.positions;
    six_volume += p[f.vertices[0]].dot(p[f.vertices[1]].cross(p[f.vertices[2]]));
  }
  HS_CHECK(six_volume > 0);
}

Isometry3d Pose(const Vector3d& translation, const Eigen::AngleAxisd& rotation) {
  Isometry3d X = Isometry3d::Identity();
  X.translate(translation);
  X.rotate(rotation);
  return X;
}

std::unique_ptr<Body> MakeBody(const char* name, MeshInput mesh, const Isometry3d& X_WO) {
  CheckOutward(mesh);
  absl::StatusOr<HapticObject> object = HapticObject::Create(name, std::move(mesh));
  HS_CHECK(object.ok());
  // The margin contact_test_bodies.h uses: room for relative tolerances up
  // to 1e-6, far above the 1e-9 queried here.
  const double margin = 1e-6 * object->bounding_box().diagonal().norm();
  CollisionModel model(*object, BvType::kObbRss, margin);

  // FCL gets no margin: its exhaustive mode is timed as FCL users run it.
  auto bvh = std::make_shared<FclBvh>();
  std::vector<fcl::Vector3d> vertices(object->positions().begin(), object->positions().end());
  std::vector<fcl::Triangle> triangles;
  for (const Face& f : object->faces()) {
    triangles.emplace_back(f.vertices[0], f.vertices[1], f.vertices[2]);
  }
  HS_CHECK(bvh->beginModel(object->num_faces(), object->num_vertices()) == fcl::BVH_OK);
  HS_CHECK(bvh->addSubModel(vertices, triangles) == fcl::BVH_OK);
  HS_CHECK(bvh->endModel() == fcl::BVH_OK);
  return std::make_unique<Body>(Body{*std::move(object), std::move(model), X_WO, std::move(bvh)});
}

// The fixed object of cases 1-3: a 4 x 4 x 1 slab with its top face at z = 0.
std::unique_ptr<Body> Slab() {
  return MakeBody("slab", MakeBox(Vector3d(4, 4, 1)),
                  Pose(Vector3d(0, 0, -0.5), Eigen::AngleAxisd::Identity()));
}

const Vector3d kDown(0, 0, -1);

std::unique_ptr<Case> MakeCase(int index) {
  auto c = std::make_unique<Case>();
  switch (index) {
    case 0: {
      // #1, one point of two convex objects: the apex of a 32-sided cone
      // pressed 1 cm into the slab's top face, away from the face's
      // diagonal, so that exactly its 32 side edges cross the face.
      c->name = "case1";
      c->description = "cone apex (valence 32) into a face";
      c->paper = {32, 22, 0.00015};
      c->moving = MakeBody("cone", MakeCone(0.5, 1.0, 32),
                           Pose(Vector3d(0.3, -0.4, -0.01), Eigen::AngleAxisd::Identity()));
      c->fixed = Slab();
      c->direction_W = kDown;
      break;
    }
    case 1: {
      // #2, a line: a 16-sided cylinder in 12 slices lying on its side, its
      // lowest row of 13 vertices (k = 12, angle -pi/2) pressed 5 mm into
      // the face. The next rows up are 19 mm higher, so only that row is in.
      const double radius = 0.25, depth = 0.005;
      c->name = "case2";
      c->description = "cylinder edge line (12 edges) on a face";
      c->paper = {54, 31, 0.00031};
      c->moving = MakeBody("cylinder", MakeCylinder(radius, 1.5, 16, 12),
                           Pose(Vector3d(0.5, -0.6, radius - depth),
                                Eigen::AngleAxisd(std::numbers::pi / 6, Vector3d::UnitZ())));
      c->fixed = Slab();
      c->direction_W = kDown;
      break;
    }
    case 2: {
      // #3, many points of a non-convex object: a torus of 100 x 24 quads
      // (4,800 faces) lying on the slab, its lowest ring of 100 vertices
      // pressed 4 mm in (the next rings are 8.5 mm higher).
      const double minor = 0.25, depth = 0.004;
      c->name = "case3";
      c->description = "torus 100x24 lying on a face (ring of 100 vertices)";
      c->paper = {409, 205, 0.991};
      c->moving = MakeBody(
          "torus", MakeTorus(1.0, minor, 100, 24),
          Pose(Vector3d(0.2, 0.1, minor - depth), Eigen::AngleAxisd(0.1, Vector3d::UnitZ())));
      c->fixed = Slab();
      c->direction_W = kDown;
      break;
    }
    case 3: {
      // #4, the largest, two non-convex objects: two tori of 125 x 15 quads
      // (3,750 faces each) stacked like O-rings pressed 3 cm together (2.6 cm
      // between the meshes, whose 15-gon tubes lie inside the round ones), the
      // upper one offset by 6 cm and turned half a segment so that no
      // features coincide. Their tubes cut each other along two curves that
      // run all the way round, crossing about 1,000 edges. Linked tori (chain
      // links) were tried first: their tubes meet only where they cross, two
      // patches of 300-480 colliding edges at this size, and no translation
      // separates linked rings, so the reversing vector means nothing there.
      const double minor = 0.35, depth = 0.03;
      c->name = "case4";
      c->description = "two tori 125x15 (3,750 faces each) pressed together all round";
      c->paper = {1062, 502, 5.00};
      const Isometry3d X = Pose(Vector3d(0.05, 0.035, 2 * minor - depth),
                                Eigen::AngleAxisd(std::numbers::pi / 125, Vector3d::UnitZ()));
      c->moving = MakeBody("upper_torus", MakeTorus(1.0, minor, 125, 15), X);
      c->fixed = MakeBody("lower_torus", MakeTorus(1.0, minor, 125, 15), Isometry3d::Identity());
      c->direction_W = kDown;
      break;
    }
    default:
      HS_CHECK(false);
  }
  return c;
}

}  // namespace

const Case& GetCase(int index) {
  static std::array<std::unique_ptr<Case>, kNumCases> cases;
  if (!cases[index]) cases[index] = MakeCase(index);
  return *cases[index];
}

// The tolerance ComputeContact derives from the query: relative to the
// pair's size, the sum of the two objects' box diagonals.
double ToleranceM(const Case& c) {
  return kRelativeTolerance * (c.moving->object.bounding_box().diagonal().norm() +
                               c.fixed->object.bounding_box().diagonal().norm());
}

ContactQuery Query(const Case& c, ContactMethod method) {
  return ContactQuery{
      .direction_W = c.direction_W, .method = method, .relative_tolerance = kRelativeTolerance};
}

const std::vector<Isometry3d>& CoherentPoses(int index) {
  static std::array<std::vector<Isometry3d>, kNumCases> poses;
  std::vector<Isometry3d>& out = poses[index];
  if (out.empty()) {
    const Isometry3d& X0 = GetCase(index).moving->X_WO;
    for (int k = 0; k < kCoherentSteps; ++k) {
      const double t = k * kCoherentStepS;
      Isometry3d X = X0;
      X.translation() += Vector3d(kSlideMps * t, 0, 0);
      X.linear() =
          Eigen::AngleAxisd(kTurnRadPs * t, Vector3d::UnitZ()).toRotationMatrix() * X0.linear();
      out.push_back(X);
    }
  }
  return out;
}

}  // namespace hs::table1
