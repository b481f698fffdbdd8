// The free-body part of Scene::Step: each body's motion and the serial
// resolution of its contacts (paper s.5).

#include <algorithm>
#include <cmath>

#include "common/sim/motion_bounds.h"
#include "common/sim/scene.h"
#include "common/sim/touched_face.h"

namespace hs {
namespace {

// Below this cosine between the body's motion and the inward normal, the
// depth along the motion is too long a way round: measure it along the
// normal instead.
constexpr double kMinInto = 0.1;

}  // namespace

void Scene::AddPushReaction(const Tool& tool, ToolFrame& frame) const {
  if (tool.push_impulse_W.isZero()) return;
  // The bodies push back with the impulse they took, spread over the step.
  Vector3d force = frame.force_W - tool.push_impulse_W / options_.step_s;
  if (force.norm() > options_.force_clamp_n) {
    force *= options_.force_clamp_n / force.norm();
    frame.force_clamped = true;
  }
  frame.force_W = force;
}

void Scene::MoveFreeBody(Body& body, BodyFrame& frame) {
  frame.body = body.id;
  frame.contacts = 0;
  // Keep each sub-step's travel under the shortest box edge of any object
  // (paper s.4): the travel is estimated from the velocity after gravity.
  const double dt = options_.step_s;
  const double travel = (body.state.v_W + dt * options_.gravity_W).norm() * dt;
  constexpr int kMaxBodySubsteps = 64;
  frame.substeps = SubstepCount(travel, smallest_edge_m_, kMaxBodySubsteps);
  const double h = dt / frame.substeps;
  for (int sub = 0; sub < frame.substeps; ++sub) {
    const Isometry3d X_WO_from = body.state.X_WO;
    IntegrateFreeBody(body.mass, options_.gravity_W, h, body.state);
    int touching = 0;
    for (ObjectId other = 0; other < static_cast<ObjectId>(objects_.size()); ++other) {
      if (other != body.id) touching += ResolveContact(body, X_WO_from, other);
    }
    if (touching > 0) body.state.w_W *= std::exp(-options_.contact_angular_damping_per_s * h);
    frame.contacts += touching;
  }
  objects_[body.id]->X_WO = body.state.X_WO;
  frame.X_WO = body.state.X_WO;
  frame.v_W = body.state.v_W;
  frame.w_W = body.state.w_W;
}

Scene::Counterpart Scene::CounterpartOf(ObjectId id) {
  const Object& o = *objects_[id];
  Counterpart c;
  c.X_WO = o.X_WO;
  switch (o.kind) {
    case ObjectKind::kFixed:
      break;
    case ObjectKind::kTool: {
      const Tool& tool = tools_[slots_[id]];
      c.X_WO = tool.X_WP;
      c.motion_W = tool.X_WP.translation() - tool.X_WP_previous.translation();
      c.v_W = c.motion_W / options_.step_s;
      break;
    }
    case ObjectKind::kFree: {
      Body& other = bodies_[slots_[id]];
      c.X_WO = other.state.X_WO;
      c.motion_W = other.state.X_WO.translation() - other.X_WO_start.translation();
      c.body = {&other.mass, &other.state};
      break;
    }
  }
  return c;
}

double Scene::SeparationAlongNormal(const Object& self, const Isometry3d& X_WO, const Object& that,
                                    const Isometry3d& X_WO_other, const ContactSet& contact,
                                    const Vector3d& motion_W, const Vector3d& n) const {
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
  const absl::StatusOr<ContactSet> again =
      ComputeContact(Posed(self, X_WO), Posed(that, X_WO_other), along_normal);
  if (!again.ok() || !again->penetrating) return std::max(0.0, separation);
  return std::max(0.0, again->reversing_vector_W.dot(n));
}

bool Scene::ResolveContact(Body& body, const Isometry3d& X_WO_from, ObjectId other) {
  const Object& self = *objects_[body.id];
  const Object& that = *objects_[other];
  const Counterpart c = CounterpartOf(other);
  // Boxes apart (grown by the margins that cover the touching tolerance):
  // no contact, without asking the narrow phase.
  if (options_.broad_phase &&
      !GrowBox(WorldBox(self.object, body.state.X_WO), self.model.margin_m())
           .intersects(GrowBox(WorldBox(that.object, c.X_WO), that.model.margin_m()))) {
    return false;
  }
  // The body's motion relative to the other object: the direction the
  // reversing vector undoes.
  const ContactQuery query{
      .direction_W = body.state.X_WO.translation() - X_WO_from.translation() - c.motion_W,
      .method = options_.method,
      .relative_tolerance = options_.relative_tolerance};
  const absl::StatusOr<ContactSet> contact =
      ComputeContact(Posed(self, body.state.X_WO), Posed(that, c.X_WO), query);
  if (!contact.ok() || !contact->colliding || contact->normal_W.isZero()) return false;
  BodyContact response;
  response.normal_W = FaceSideNormal(that.object, contact->fixed, c.X_WO);
  if (response.normal_W.isZero()) response.normal_W = contact->normal_W;
  // The normal share of the reversing vector: moving back along the whole
  // vector would also undo the body's sliding along the surface.
  if (contact->penetrating) {
    response.separation_m = SeparationAlongNormal(self, body.state.X_WO, that, c.X_WO, *contact,
                                                  query.direction_W, response.normal_W);
  }
  response.p_WC = CentreOfMass(body.mass, body.state);
  if (!contact->points.empty()) {
    Vector3d sum = Vector3d::Zero();
    for (const ContactPoint& p : contact->points) sum += p.p_WC;
    response.p_WC = sum / static_cast<double>(contact->points.size());
  }
  response.v_other_W = c.v_W;
  response.friction =
      that.object.face_material(TouchedFace(that.object, contact->fixed)).dynamic_friction;
  const Vector3d impulse = RespondToContact(body.mass, response, body.state, c.body);
  if (that.kind == ObjectKind::kTool) tools_[slots_[other]].push_impulse_W += impulse;
  return true;
}

}  // namespace hs
