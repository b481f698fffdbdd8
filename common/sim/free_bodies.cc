#include "common/sim/free_bodies.h"

#include <algorithm>
#include <cmath>

#include "common/sim/motion_bounds.h"
#include "common/sim/tool_force.h"
#include "common/sim/touched_face.h"

namespace hs {
namespace {

// Below this cosine between the body's motion and the inward normal, the
// depth along the motion is too long a way round: measure it along the
// normal instead.
constexpr double kMinInto = 0.1;
// A body's step is split into at most this many sub-steps.
constexpr int kMaxBodySubsteps = 64;

}  // namespace

void FreeBodies::Add(ObjectId id, const MassProperties& mass, const FreeBodyState& start) {
  if (static_cast<int>(index_.size()) <= id) index_.resize(id + 1, -1);
  index_[id] = static_cast<int>(bodies_.size());
  bodies_.push_back(Body{id, mass, start, start.X_WO});
}

Vector3d FreeBodies::PushImpulseOf(ObjectId id) const {
  return id < static_cast<ObjectId>(push_impulse_W_.size()) ? push_impulse_W_[id]
                                                            : Vector3d::Zero();
}

void FreeBodies::Step(const ToolStage& tools, std::vector<BodyFrame>& frames) {
  frames.resize(bodies_.size());
  push_impulse_W_.assign(objects_.size(), Vector3d::Zero());
  for (Body& body : bodies_) body.X_WO_start = body.state.X_WO;
  for (size_t i = 0; i < bodies_.size(); ++i) Move(bodies_[i], tools, frames[i]);
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
    int touching = 0;
    for (ObjectId other = 0; other < objects_.size(); ++other) {
      if (other == body.id || !ResolveContact(body, X_WO_from, h, other, tools)) continue;
      ++touching;
      const auto at = std::lower_bound(frame.touching.begin(), frame.touching.end(), other);
      if (at == frame.touching.end() || *at != other) frame.touching.insert(at, other);
    }
    if (touching > 0) body.state.w_W *= std::exp(-options_.contact_angular_damping_per_s * h);
    frame.contacts += touching;
  }
  objects_.MoveBody(body.id, body.state.X_WO);
  frame.X_WO = body.state.X_WO;
  frame.v_W = body.state.v_W;
  frame.w_W = body.state.w_W;
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

double FreeBodies::SeparationAlongNormal(ObjectId self, const Isometry3d& X_WO, ObjectId that,
                                         const Isometry3d& X_WO_other, const ContactSet& contact,
                                         const Vector3d& motion_W, const Vector3d& n) {
  // A motion that goes into the surface: the reversing vector's normal
  // share is the depth along the normal.
  const double into = -motion_W.normalized().dot(n);
  const double separation = contact.reversing_vector_W.dot(n);
  if (into >= kMinInto && separation > 0) return separation;
  // A motion along or out of the surface (a body pushed in by another
  // after its own resolution, or sliding): the depth straight along the
  // normal, by a query moving the body into the surface.
  const ContactQuery along_normal{.direction_W = -n,
                                  .method = options_.method,
                                  .relative_tolerance = options_.relative_tolerance};
  ContactSet& again = along_normal_;
  const absl::Status status = ComputeContact(objects_.Posed(self, X_WO),
                                             objects_.Posed(that, X_WO_other), along_normal, again);
  if (!status.ok() || !again.penetrating) return std::max(0.0, separation);
  return std::max(0.0, again.reversing_vector_W.dot(n));
}

bool FreeBodies::ResolveContact(Body& body, const Isometry3d& X_WO_from, double h, ObjectId other,
                                const ToolStage& tools) {
  const HapticObject& that = objects_[other].object;
  const Counterpart c = CounterpartOf(other, tools);
  // Boxes apart (grown by the margins that cover the touching tolerance):
  // no contact, without asking the narrow phase.
  if (options_.broad_phase &&
      !objects_.GrownBox(body.id, body.state.X_WO).intersects(objects_.GrownBox(other, c.X_WO))) {
    return false;
  }
  // The body's motion relative to the other object: the direction the
  // reversing vector undoes. A tool presses: the body is taken as having
  // come at it straight, centre to centre, so that the depth is the
  // press's and not a long way round along a motion mostly beside it.
  const bool tool = objects_[other].kind == ObjectKind::kTool;
  const ContactQuery query{
      .direction_W =
          tool ? Vector3d(c.X_WO.translation() - CentreOfMass(body.mass, body.state))
               : Vector3d(body.state.X_WO.translation() - X_WO_from.translation() - c.motion_W),
      .method = options_.method,
      .relative_tolerance = options_.relative_tolerance};
  const absl::Status status = ComputeContact(objects_.Posed(body.id, body.state.X_WO),
                                             objects_.Posed(other, c.X_WO), query, contact_);
  const ContactSet& contact = contact_;
  if (!status.ok() || !contact.colliding || contact.normal_W.isZero()) return false;
  BodyContact response;
  response.normal_W = FaceSideNormal(that, contact.fixed, c.X_WO);
  if (response.normal_W.isZero()) response.normal_W = contact.normal_W;
  // The normal share of the reversing vector: moving back along the whole
  // vector would also undo the body's sliding along the surface.
  if (contact.penetrating) {
    response.separation_m = SeparationAlongNormal(body.id, body.state.X_WO, other, c.X_WO, contact,
                                                  query.direction_W, response.normal_W);
  }
  response.p_WC = CentreOfMass(body.mass, body.state);
  if (!contact.points.empty()) {
    Vector3d sum = Vector3d::Zero();
    for (const ContactPoint& p : contact.points) sum += p.p_WC;
    response.p_WC = sum / static_cast<double>(contact.points.size());
  }
  response.v_other_W = c.v_W;
  const Material& touched = that.face_material(TouchedFace(that, contact.fixed));
  response.friction = touched.dynamic_friction;
  // A tool in the body squeezes it with the spring of the two faces in
  // series over its depth, as a proxy held out of the body would feel.
  if (tool && response.separation_m > 0) {
    const HapticObject& self = objects_[body.id].object;
    const Material pair =
        TouchingMaterial(touched, self.face_material(TouchedFace(self, contact.moving)));
    response.grip_impulse = pair.stiffness_n_per_m * response.separation_m * h;
  }
  const Vector3d impulse = RespondToContact(body.mass, response, body.state, c.body);
  if (tool) push_impulse_W_[other] += impulse + response.grip_impulse * response.normal_W;
  return true;
}

}  // namespace hs
