#include "common/sim/free_bodies.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/sim/motion_bounds.h"
#include "common/sim/tool_force.h"
#include "common/sim/touched_face.h"

namespace hs {
namespace {

// A body's step is split into at most this many sub-steps.
constexpr int kMaxBodySubsteps = 64;
// Beyond its own travel in a sub-step, how much older penetration of a
// fixed object or another body a contact point may shed in one sub-step,
// metres: the push's cap, so that no wrong depth throws a body far.
constexpr double kMaxRecoveryM = 1e-3;
// A point kept from the last sub-step stays a contact while it is within
// this of the face's plane, metres (a tilt of 5 mrad over a 2 cm face), has
// not slid farther than kMaxSlideM from where it was last found, and is
// not within kSamePointM of a point found again.
constexpr double kKeepWithinM = 1e-4;
constexpr double kMaxSlideM = 1e-3;
constexpr double kSamePointM = 1e-6;
// A body's face counts as lying on the other's face when their normals are
// within this cosine of opposite (about 2.6 degrees).
constexpr double kFacingCosine = 0.999;
// Cosine above which a query's direction counts as along the normal.
constexpr double kAlongNormal = 1 - 1e-12;

// Two unit tangents of the unit normal n, the first across the world axis
// least along n: a face square to the world axes gets tangents along its
// edges, so that a box's contact patch and its corners line up with them.
void FaceTangents(const Vector3d& n, Vector3d& t1, Vector3d& t2) {
  const Eigen::Index axis = n.cwiseAbs().minCoeff() == std::abs(n.x())   ? 0
                            : n.cwiseAbs().minCoeff() == std::abs(n.y()) ? 1
                                                                         : 2;
  t1 = n.cross(Vector3d::Unit(axis)).normalized();
  t2 = n.cross(t1);
}

}  // namespace

void FreeBodies::Add(ObjectId id, const MassProperties& mass, const FreeBodyState& start) {
  if (static_cast<int>(index_.size()) <= id) index_.resize(id + 1, -1);
  index_[id] = static_cast<int>(bodies_.size());
  bodies_.push_back(Body{id, mass, start, start.X_WO, {}});
}

Vector3d FreeBodies::PushImpulseOf(ObjectId id) const {
  return id < static_cast<ObjectId>(push_impulse_W_.size()) ? push_impulse_W_[id]
                                                            : Vector3d::Zero();
}

void FreeBodies::Step(const ToolStage& tools, std::vector<BodyFrame>& frames) {
  frames.resize(bodies_.size());
  push_impulse_W_.assign(objects_.size(), Vector3d::Zero());
  for (Body& body : bodies_) {
    body.X_WO_start = body.state.X_WO;
    // Grows only when objects were added since the last step.
    body.pairs.resize(objects_.size());
  }
  for (size_t i = 0; i < bodies_.size(); ++i) Move(bodies_[i], tools, frames[i]);
  // A body moved later in the step may have pushed one moved earlier: the
  // frames and the scene's poses are written once all have moved.
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const Body& body = bodies_[i];
    objects_.MoveBody(body.id, body.state.X_WO);
    frames[i].X_WO = body.state.X_WO;
    frames[i].v_W = body.state.v_W;
    frames[i].w_W = body.state.w_W;
  }
}

void FreeBodies::Move(Body& body, const ToolStage& tools, BodyFrame& frame) {
  frame.body = body.id;
  frame.contacts = 0;
  frame.touching.clear();
  // Keep each sub-step's travel under the shortest box edge of any object
  // (paper s.4): the travel is estimated from the velocity after gravity.
  const double dt = options_.step_s;
  const double travel = (body.state.v_W + dt * options_.gravity_W).norm() * dt;
  frame.substeps = SubstepCount(travel, objects_.smallest_edge_m(), kMaxBodySubsteps);
  const double h = dt / frame.substeps;
  for (int sub = 0; sub < frame.substeps; ++sub) {
    const Isometry3d X_WO_from = body.state.X_WO;
    IntegrateFreeBody(body.mass, options_.gravity_W, h, body.state);
    contacts_.clear();
    int touching = 0;
    for (ObjectId other = 0; other < objects_.size(); ++other) {
      if (other == body.id || !GatherContact(body, X_WO_from, h, frame.substeps, other, tools)) {
        continue;
      }
      ++touching;
      const auto at = std::lower_bound(frame.touching.begin(), frame.touching.end(), other);
      if (at == frame.touching.end() || *at != other) frame.touching.insert(at, other);
    }
    solver_.Solve(body.mass, body.state, contacts_, h);
    for (const SolverContact& contact : contacts_) {
      if (contact.side == ContactSide::kTool) push_impulse_W_[contact.tag] += contact.impulse_W;
    }
    if (touching > 0) body.state.w_W *= std::exp(-options_.contact_angular_damping_per_s * h);
    frame.contacts += touching;
  }
}

FreeBodies::Counterpart FreeBodies::CounterpartOf(ObjectId id, const ToolStage& tools) {
  const SceneObjects::Object& o = objects_[id];
  Counterpart c;
  c.X_WO = o.X_WO;
  switch (o.kind) {
    case ObjectKind::kFixed:
      break;
    case ObjectKind::kTool: {
      const ToolStage::ProxyMotion proxy = tools.ProxyMotionOf(id);
      c.X_WO = proxy.X_WP;
      c.motion_W = proxy.motion_W;
      c.v_W = c.motion_W / options_.step_s;
      break;
    }
    case ObjectKind::kFree: {
      Body& other = bodies_[index_[id]];
      c.X_WO = other.state.X_WO;
      c.motion_W = other.state.X_WO.translation() - other.X_WO_start.translation();
      c.body = {&other.mass, &other.state};
      break;
    }
  }
  return c;
}

Vector3d FreeBodies::NormalOf(const Body& body, ObjectId other, const Isometry3d& X_WO_other,
                              const ContactSet& contact) const {
  Vector3d n = FaceSideNormal(objects_[other].object, contact.fixed, X_WO_other);
  if (n.isZero()) n = -FaceSideNormal(objects_[body.id].object, contact.moving, body.state.X_WO);
  if (n.isZero()) n = contact.normal_W;
  return n;
}

void FreeBodies::AddFaceCorners(const Body& body, const SideContact& side, ObjectId other,
                                const SideContact& other_side, const Vector3d& n, double plane,
                                double depth, const Isometry3d& X_WO_other) {
  const HapticObject& self = objects_[body.id].object;
  const HapticObject& that = objects_[other].object;
  const Isometry3d X_FW = X_WO_other.inverse();
  // The faces at the contact (those of its features) that face each
  // other: the body's turned against n, the other's along it, in the world.
  facing_self_.clear();
  facing_other_.clear();
  auto collect = [&](const HapticObject& object, const Isometry3d& X_WO, const SideContact& at,
                     double sign, std::vector<Triangle>& out) {
    auto add = [&](FaceId f) {
      const auto& v = object.face(f).vertices;
      const Triangle t{X_WO * object.position(v[0]), X_WO * object.position(v[1]),
                       X_WO * object.position(v[2])};
      const Vector3d normal = (t[1] - t[0]).cross(t[2] - t[0]);
      if (!(sign * normal.dot(n) > kFacingCosine * normal.norm())) return;
      for (const Triangle& known : out) {
        if (known == t) return;
      }
      out.push_back(t);
    };
    for (const VertexId v : at.vertices) {
      for (const FaceId f : object.VertexFaces(v)) add(f);
    }
    for (const EdgeId e : at.edges) {
      for (const FaceId f : object.EdgeFaces(e)) add(f);
    }
    for (const FaceId f : at.faces) add(f);
  };
  collect(self, body.state.X_WO, side, -1, facing_self_);
  collect(that, X_WO_other, other_side, 1, facing_other_);
  // Whether p, moved along n, falls in one of `faces`.
  auto over = [&](const Vector3d& p, const std::vector<Triangle>& faces) {
    for (const Triangle& t : faces) {
      const Vector3d q = p - n.dot(p - t[0]) * n;
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const Vector3d& a = t[k];
        const Vector3d& b = t[(k + 1) % 3];
        // Inside or on an edge, within the point-merging distance.
        const Vector3d edge = b - a;
        inside = n.dot(edge.cross(q - a)) * n.dot(edge.cross(t[(k + 2) % 3] - a)) >=
                 -kSamePointM * edge.norm() * edge.norm() * edge.norm();
      }
      if (inside) return true;
    }
    return false;
  };
  auto add_point = [&](const Vector3d& p_W, double point_depth) {
    for (const PairPoint& p : points_) {
      if ((p.p_W - p_W).norm() < kSamePointM) return;
    }
    points_.push_back({p_W, point_depth, X_FW * p_W});
  };
  for (const Triangle& t : facing_self_) {
    for (const Vector3d& p_W : t) {
      const double height = n.dot(p_W) - plane;
      if (height <= kKeepWithinM && over(p_W, facing_other_)) {
        add_point(p_W, std::min(depth, -height));
      }
    }
  }
  // The other's corners over the body's face: there the body's face lies
  // `depth` under them.
  for (const Triangle& t : facing_other_) {
    for (const Vector3d& corner : t) {
      const Vector3d p_W = corner - depth * n;
      if (over(p_W, facing_self_)) add_point(p_W, depth);
    }
  }
}

// At most eight points, the farthest along eight directions on the face:
// the query may report a point twice (two feature pairs) or add points
// where the faces' triangulations cross, which would load one side of a
// face more than the other.
void FreeBodies::KeepEightPoints(const Vector3d& n) {
  if (points_.size() <= 1) return;
  Vector3d t1, t2;
  FaceTangents(n, t1, t2);
  const std::array<Vector3d, 8> directions = {t1,      -t1,     t2,       -t2,
                                              t1 + t2, t1 - t2, -t1 + t2, -t1 - t2};
  std::array<int, directions.size()> picked;
  int unique = 0;
  for (const Vector3d& d : directions) {
    int best = 0;
    for (size_t i = 1; i < points_.size(); ++i) {
      if (d.dot(points_[i].p_W) > d.dot(points_[best].p_W) + kSamePointM) {
        best = static_cast<int>(i);
      }
    }
    // Kept sorted as picked (an insertion into at most 7 picks), so that the
    // copies below never overwrite a point still to be copied.
    const auto end = picked.begin() + unique;
    const auto at = std::lower_bound(picked.begin(), end, best);
    if (at == end || *at != best) {
      std::copy_backward(at, end, end + 1);
      *at = best;
      ++unique;
    }
  }
  for (int k = 0; k < unique; ++k) points_[k] = points_[picked[k]];
  points_.resize(unique);
}

bool FreeBodies::GatherContact(Body& body, const Isometry3d& X_WO_from, double h, int substeps,
                               ObjectId other, const ToolStage& tools) {
  const HapticObject& that = objects_[other].object;
  const ObjectKind kind = objects_[other].kind;
  const Counterpart c = CounterpartOf(other, tools);
  PairMemory& memory = body.pairs[other];
  // Boxes apart (grown by the margins that cover the touching tolerance):
  // no contact, without asking the narrow phase.
  if (options_.broad_phase &&
      !objects_.GrownBox(body.id, body.state.X_WO).intersects(objects_.GrownBox(other, c.X_WO))) {
    memory = PairMemory{};
    return false;
  }
  // Where to look for the contact's face: along the last normal while a
  // contact lasts (its face stays the one that pushes, however the body
  // slides along it); a tool's new contact as a press met straight, centre
  // to centre; another's along the relative motion.
  const Vector3d c_W = CentreOfMass(body.mass, body.state);
  Vector3d direction = -memory.normal_W;
  if (memory.normal_W.isZero()) {
    direction =
        kind == ObjectKind::kTool
            ? Vector3d(c.X_WO.translation() - c_W)
            : Vector3d(body.state.X_WO.translation() - X_WO_from.translation() - c.motion_W);
  }
  const PosedObject self_posed = objects_.Posed(body.id, body.state.X_WO);
  const PosedObject other_posed = objects_.Posed(other, c.X_WO);
  const ContactQuery query{.direction_W = direction,
                           .method = options_.method,
                           .relative_tolerance = options_.relative_tolerance};
  absl::Status status = ComputeContact(self_posed, other_posed, query, contact_);
  if (!status.ok() || !contact_.colliding) {
    memory = PairMemory{};
    return false;
  }
  const Vector3d n = NormalOf(body, other, c.X_WO, contact_);
  if (n.isZero()) {
    memory = PairMemory{};
    return false;
  }
  // The depth along the face's own normal: a depth along a motion mostly
  // beside the face would run a long way round, out through the other
  // object's far side.
  const ContactSet* found = &contact_;
  if (contact_.penetrating && -n.dot(contact_.direction_W) < kAlongNormal) {
    const ContactQuery along_normal{.direction_W = -n,
                                    .method = options_.method,
                                    .relative_tolerance = options_.relative_tolerance};
    status = ComputeContact(self_posed, other_posed, along_normal, along_normal_);
    if (status.ok() && along_normal_.colliding) found = &along_normal_;
  }
  const double depth = found->penetrating ? std::max(0.0, found->reversing_vector_W.dot(n)) : 0.0;
  // The found points, back on the body (they are where the two touch once
  // separated), then the kept ones still within reach of the face's plane
  // and not slid far from where they were last found.
  const Isometry3d X_OW = body.state.X_WO.inverse();
  const Isometry3d X_FW = c.X_WO.inverse();
  // n . x on the face's plane: the found points lie on it once separated.
  double plane = 0;
  for (const ContactPoint& p : found->points) plane += n.dot(p.p_WC);
  plane /= static_cast<double>(std::max<size_t>(1, found->points.size()));
  points_.clear();
  for (const ContactPoint& p : found->points) {
    const Vector3d p_W = p.p_WC - found->reversing_vector_W;
    points_.push_back({p_W, depth, X_FW * p_W});
  }
  for (int k = 0; k < (found->points.empty() ? 0 : memory.points); ++k) {
    const Vector3d p_W = body.state.X_WO * memory.p_O[k];
    const double height = n.dot(p_W) - plane;  // above the plane: > 0
    Vector3d slid = c.X_WO * memory.p_F[k] - p_W;
    slid -= n.dot(slid) * n;
    if (height > kKeepWithinM || slid.norm() > kMaxSlideM) continue;
    bool near_found = false;
    for (const ContactPoint& p : found->points) {
      near_found |= (p.p_WC - found->reversing_vector_W - p_W).norm() < kSamePointM;
    }
    if (!near_found) points_.push_back({p_W, std::min(depth, -height), memory.p_F[k]});
  }
  if (!found->points.empty()) {
    AddFaceCorners(body, found->moving, other, found->fixed, n, plane, depth, c.X_WO);
  }
  if (points_.empty()) points_.push_back({c_W, depth, X_FW * c_W});
  KeepEightPoints(n);
  memory.normal_W = n;
  memory.points = static_cast<int>(points_.size());
  for (int k = 0; k < memory.points; ++k) {
    memory.p_O[k] = X_OW * points_[k].p_W;
    memory.p_F[k] = points_[k].p_F;
  }

  const Material& touched = that.face_material(TouchedFace(that, found->fixed));
  SolverContact point;
  point.normal_W = n;
  point.friction = touched.dynamic_friction;
  point.tag = other;
  const double count = static_cast<double>(points_.size());
  switch (kind) {
    case ObjectKind::kFixed:
      point.side = ContactSide::kFixed;
      break;
    case ObjectKind::kFree:
      point.side = ContactSide::kBody;
      point.other = c.body;
      break;
    case ObjectKind::kTool: {
      point.side = ContactSide::kTool;
      point.v_other_W = c.v_W;
      // The tool pushes the body out at most as far as it advanced along
      // the normal, spread over the step's sub-steps.
      point.max_push_m = std::max(0.0, c.motion_W.dot(n)) / substeps;
      // A tool in the body squeezes it with the spring of the two faces in
      // series over its depth, as a proxy held out of the body would feel.
      const HapticObject& self = objects_[body.id].object;
      const Material pair =
          TouchingMaterial(touched, self.face_material(TouchedFace(self, found->moving)));
      point.grip_impulse = pair.stiffness_n_per_m * depth * h / count;
      break;
    }
  }
  const Isometry3d X_from_now = X_WO_from * X_OW;
  for (const PairPoint& p : points_) {
    point.p_WC = p.p_W;
    point.depth_m = p.depth_m;
    if (kind != ObjectKind::kTool) {
      // The point's own travel this sub-step, and the other's, bound how
      // far it may have gone in.
      point.max_push_m = (p.p_W - X_from_now * p.p_W).norm() + c.motion_W.norm() + kMaxRecoveryM;
    }
    contacts_.push_back(point);
  }
  return true;
}

}  // namespace hs
