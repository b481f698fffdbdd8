#pragma once
// The free bodies of a scene and their step (paper s.5): each body falls
// under gravity in sub-steps short enough not to pass through anything,
// and after each sub-step resolves its contact with every other object,
// serially in id order, so that a body moved earlier meets the others
// where they are now. Tools are met at their proxies and take the
// impulses they give back (the push reaction on the device).

#include <vector>

#include "common/sim/free_body.h"
#include "common/sim/scene_objects.h"
#include "common/sim/scene_options.h"
#include "common/sim/tool_stage.h"

namespace hs {

class FreeBodies {
 public:
  /// `objects` outlives this; the bodies' moves are written to it.
  FreeBodies(const SceneOptions& options, SceneObjects& objects)
      : options_(options), objects_(objects) {}

  /// Makes object `id` (a free body of `objects`) a body of `mass` starting
  /// in `start`.
  void Add(ObjectId id, const MassProperties& mass, const FreeBodyState& start);
  bool empty() const { return bodies_.empty(); }
  size_t size() const { return bodies_.size(); }

  /// Moves every body one step, meeting the tools of `tools` at their
  /// proxies; `frames` takes one entry per body, in the order added.
  void Step(const ToolStage& tools, std::vector<BodyFrame>& frames);

  /// The impulse the bodies took from tool `id` in the last Step, world
  /// frame, N*s (zero when it pushed none).
  Vector3d PushImpulseOf(ObjectId id) const;

 private:
  struct Body {
    ObjectId id;
    MassProperties mass;
    FreeBodyState state;
    Isometry3d X_WO_start;  // pose at the start of the current step
  };
  // The other side of a body's contact, as the response needs it.
  struct Counterpart {
    Isometry3d X_WO = Isometry3d::Identity();
    Vector3d motion_W = Vector3d::Zero();  // its displacement this step, metres
    Vector3d v_W = Vector3d::Zero();       // its velocity, m/s (tools)
    OtherBody body;                        // set when it is free
  };

  void Move(Body& body, const ToolStage& tools, BodyFrame& frame);
  Counterpart CounterpartOf(ObjectId id, const ToolStage& tools);
  // Resolves one contact of `body` (moved from X_WO_from this sub-step of
  // h seconds) with object `other`; returns whether they were in contact.
  bool ResolveContact(Body& body, const Isometry3d& X_WO_from, double h, ObjectId other,
                      const ToolStage& tools);
  // How far to move object `self` (at X_WO) along the unit normal n to stop
  // penetrating object `that`, from `contact` found along `motion_W`.
  double SeparationAlongNormal(ObjectId self, const Isometry3d& X_WO, ObjectId that,
                               const Isometry3d& X_WO_other, const ContactSet& contact,
                               const Vector3d& motion_W, const Vector3d& n);

  const SceneOptions& options_;
  SceneObjects& objects_;
  std::vector<Body> bodies_;
  // Per object id: its index in bodies_, -1 for other kinds (grown on Add).
  std::vector<int> index_;
  // Per object id: the impulse the bodies took from it this step (tools).
  std::vector<Vector3d> push_impulse_W_;
  // A contact and its depth along the normal, rewritten per query (their
  // storage kept: a step allocates nothing once they are large enough).
  ContactSet contact_;
  ContactSet along_normal_;
};

}  // namespace hs
