#pragma once
// The free bodies of a scene and their step (paper s.5): each body, in id
// order, falls under gravity in sub-steps short enough not to pass through
// anything, and after each sub-step solves its contacts with every other
// object together (contact_solver.h): a body moved earlier in the step is
// met where it is now. Each contact's normal is the touched face's own, and
// its depth is measured along that normal. Tools are met at their proxies
// and take the impulses they give back (the push reaction on the device).

#include <array>
#include <vector>

#include "common/sim/contact_solver.h"
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
  // What a body remembers of its contact with one object from the last
  // sub-step: the normal (the next query goes along it, so that a contact
  // that lasts keeps its face) and up to kPairPoints points, in the body's
  // frame and, where last found, in the other's. A face resting on a face
  // is found by the exact query at its deepest corners only once it tilts
  // by more than the touching tolerance (1e-8 rad will do); the kept
  // corners go on as speculative contacts until they part or slide away.
  static constexpr int kPairPoints = 8;
  struct PairMemory {
    Vector3d normal_W = Vector3d::Zero();  // zero: no contact
    int points = 0;
    std::array<Vector3d, kPairPoints> p_O;  // body frame, metres
    std::array<Vector3d, kPairPoints> p_F;  // the other's frame, where last found
  };
  struct Body {
    ObjectId id;
    MassProperties mass;
    FreeBodyState state;
    Isometry3d X_WO_start;  // pose at the start of the current step
    // Per object id: the body's contact with it in the last sub-step.
    std::vector<PairMemory> pairs;
  };
  // The other side of a body's contact, as the solver needs it.
  struct Counterpart {
    Isometry3d X_WO = Isometry3d::Identity();
    Vector3d motion_W = Vector3d::Zero();  // its displacement this step, metres
    Vector3d v_W = Vector3d::Zero();       // its velocity, m/s (tools)
    OtherBody body;                        // set when it is free
  };

  void Move(Body& body, const ToolStage& tools, BodyFrame& frame);
  Counterpart CounterpartOf(ObjectId id, const ToolStage& tools);
  // Adds to contacts_ the points of `body`'s contact (moved from X_WO_from
  // this sub-step of h seconds, one of `substeps`) with object `other`;
  // returns whether they touch.
  bool GatherContact(Body& body, const Isometry3d& X_WO_from, double h, int substeps,
                     ObjectId other, const ToolStage& tools);
  // Adds to points_ the corners of the body's faces at `side` (the body's
  // features of a contact) facing the other's face (normal n, n . x =
  // plane; `other` posed at X_WO_other) that lie over one of the other's
  // facing faces at `other_side` and within reach of the plane, and the
  // other's facing corners that lie over one of the body's. The exact
  // query finds a corner only within the touching tolerance, which a tilt
  // of 1e-8 rad exceeds.
  // Keeps at most eight of points_, the farthest along eight directions
  // on the face of normal `n`, in their order.
  void KeepEightPoints(const Vector3d& n);
  void AddFaceCorners(const Body& body, const SideContact& side, ObjectId other,
                      const SideContact& other_side, const Vector3d& n, double plane, double depth,
                      const Isometry3d& X_WO_other);
  // The unit normal of `contact` (body moving, `other` at X_WO_other
  // fixed), world frame, from the other toward the body: the other's
  // touched face's, else the body's own touched face's turned round, else
  // the contact set's.
  Vector3d NormalOf(const Body& body, ObjectId other, const Isometry3d& X_WO_other,
                    const ContactSet& contact) const;

  const SceneOptions& options_;
  SceneObjects& objects_;
  std::vector<Body> bodies_;
  // Per object id: its index in bodies_, -1 for other kinds (grown on Add).
  std::vector<int> index_;
  // Per object id: the impulse the bodies took from it this step (tools).
  std::vector<Vector3d> push_impulse_W_;
  // A contact and its depth along the normal, rewritten per query, the
  // contact points of one sub-step, and the solver (their storage kept: a
  // step allocates nothing once they are large enough).
  ContactSet contact_;
  ContactSet along_normal_;
  std::vector<SolverContact> contacts_;
  struct PairPoint {
    Vector3d p_W;  // on the body, world frame
    double depth_m;
    Vector3d p_F;  // in the other's frame, where last found
  };
  std::vector<PairPoint> points_;  // one pair's points
  using Triangle = std::array<Vector3d, 3>;
  std::vector<Triangle> facing_self_, facing_other_;  // AddFaceCorners's faces
  ContactSolver solver_;
};

}  // namespace hs
