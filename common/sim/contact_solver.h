#pragma once
// The contacts of one free body solved together, as one problem per body
// and (sub-)step: projected Gauss-Seidel over all its contact points
// (sequential impulses, each row's accumulated impulse clamped), first on
// velocities (inelastic normal impulses, Coulomb friction clamped to each
// point's disk, a tool's grip as the least normal impulse), then on
// positions (each contact pushes the body out along its own normal, a
// fixed object's push capped per sub-step, a tool's bounded by its own
// advance). A fixed count of iterations; buffers are kept between calls,
// so a step allocates nothing once they are large enough.

#include <span>
#include <vector>

#include "common/sim/free_body.h"

namespace hs {

/// What the other side of a body's contact is, for the solver.
enum class ContactSide {
  /// A fixed object: never gives way. Its rows are solved last in each
  /// iteration, so that neither a tool nor a body drives the body into it.
  kFixed,
  /// Another free body: takes the opposite impulses through its centre of
  /// mass (its turn is left to its own contacts, which this problem does
  /// not hold); the push out moves this body alone (the other was placed by
  /// its own contacts: a stack's lower cubes are not pressed into the
  /// floor from above).
  kBody,
  /// A tool's proxy: moves on its own and yields. Its points that follow
  /// one another with one tag and one normal are one patch, with one
  /// normal row at their centroid: its impulse is at least the points'
  /// grips and at most that plus what stops the centroid's approach at the
  /// start of the solve; it pushes the body out at most its own advance
  /// along the normal. Two tools squeezing a body thus press it with their
  /// grips instead of fighting without bound.
  kTool,
};

/// The other side when it is a free body.
struct OtherBody {
  const MassProperties* mass = nullptr;
  FreeBodyState* state = nullptr;
};

/// One contact point of the body, as the solver sees it.
struct SolverContact {
  ContactSide side = ContactSide::kFixed;
  /// Unit normal, world frame, pointing from the other object to the body:
  /// the touched face's own normal.
  Vector3d normal_W = Vector3d::UnitZ();
  /// The point, on the body at its current pose, world frame, metres.
  Vector3d p_WC = Vector3d::Zero();
  /// How far the body must move along normal_W to stop penetrating, metres
  /// (0: touching). Negative: a point kept from an earlier sub-step, apart
  /// by -depth_m; it may close that gap within the sub-step, no more (a
  /// speculative contact: a face resting slightly tilted keeps all its
  /// corners without being held up by the ones in the air).
  double depth_m = 0;
  /// The most the position pass pushes the body out here, metres, >= 0: a
  /// fixed object or body pushes min(depth_m, max_push_m); a tool at most
  /// this much.
  double max_push_m = 0;
  /// kFixed and kTool: the velocity of the other object's material at
  /// p_WC, world frame, m/s.
  Vector3d v_other_W = Vector3d::Zero();
  /// kBody: the other body (it takes the opposite impulses and pushes).
  OtherBody other;
  /// Coulomb coefficient, >= 0: the tangential impulse stays within
  /// `friction` times the normal one, point by point.
  double friction = 0;
  /// kTool: the least normal impulse at this point, N*s (the tool's
  /// squeeze over the sub-step, shared among its points).
  double grip_impulse = 0;
  /// The caller's label (e.g. the other object's id); the solver keeps it.
  int tag = -1;
  /// Out: the impulse the body took at this point in the velocity pass,
  /// normal and friction, world frame, N*s. The other side took minus it.
  Vector3d impulse_W = Vector3d::Zero();
};

struct ContactSolverOptions {
  /// Gauss-Seidel sweeps over all rows, per pass; >= 1. With 16, two jaws
  /// lifting a cube in the scene shared its weight 59 : 41; with 20, within
  /// 10 % of even (free_bodies_test).
  int iterations = 20;
};

/// Solves one body's contacts; keeps its buffers between calls.
class ContactSolver {
 public:
  explicit ContactSolver(const ContactSolverOptions& options = {}) : options_(options) {}

  /// Solves `contacts` of `body`, whose `state` holds its velocities after
  /// the sub-step's gravity and its pose at the sub-step's end (where the
  /// contacts were found); the sub-step lasts `h_s` seconds (> 0). The velocity pass changes the
  /// velocities of the body and of the free others (impulses at the points, written to each
  /// contact's impulse_W); the position pass then moves the body out
  /// (translation and turn about its centre of mass), which changes no
  /// velocity. Allocates only when `contacts` is larger
  /// than in any earlier call.
  void Solve(const MassProperties& body, FreeBodyState& state, std::span<SolverContact> contacts,
             double h_s);

 private:
  // One contact point's rows (normal, two tangents) and their accumulators.
  struct Row {
    Vector3d r = Vector3d::Zero();        // lever arm on the body, world
    Vector3d r_other = Vector3d::Zero();  // lever arm on the other body
    Vector3d t1 = Vector3d::Zero(), t2 = Vector3d::Zero();
    double k_n = 0, k_t1 = 0, k_t2 = 0;  // 1 / effective mass per direction
    double k_push = 0;                   // k_n of the body alone (position pass)
    double lo = 0, hi = 0;               // normal impulse bounds
    double closing = 0;                  // approach speed allowed (a gap's), m/s
    double normal = 0;                   // accumulated normal impulse
    double tangent1 = 0, tangent2 = 0;   // accumulated friction impulse
    double push_target = 0, push = 0;    // position pass
    int other = -1;                      // index in others_, -1 none
    int patch = -1;                      // a tool's point: index in patches_
  };
  // A tool's points on one face: one normal row at their centroid, bounded
  // as a whole (so that how many points the query found on each jaw does
  // not tip the balance); their friction rows stay point by point, each
  // within its share of the patch's normal impulse.
  struct Patch {
    int first = 0, count = 0;  // its rows
    Vector3d n = Vector3d::Zero(), r = Vector3d::Zero(), v_other = Vector3d::Zero();
    double depth = 0, max_push = 0, closing = 0;
    double k_n = 0, lo = 0, hi = 0, normal = 0;
    double push_hi = 0, push = 0;
  };
  // A free other body.
  struct Other {
    const MassProperties* mass = nullptr;
    FreeBodyState* state = nullptr;
    Vector3d c = Vector3d::Zero();  // centre of mass, world
    Matrix3d inverse_I_W = Matrix3d::Zero();
  };

  // 1 / effective mass along u at lever arm r (and r_other on the free
  // other `other`, -1 for none): how much the relative velocity there
  // changes along u per unit impulse along u.
  double Response(const Vector3d& u, const Vector3d& r, int other, const Vector3d& r_other) const;
  // The index in others_ of contact's other body, added when new.
  int OtherIndex(const SolverContact& contact);
  // Rows, patches and order_ for contacts_, the body's centre of mass at c.
  void SetUpRows(const Vector3d& c, double h_s);
  // The velocity of the body's point at lever arm r relative to the other
  // side's (a free other at r_other, else one moving at v_other).
  Vector3d RelativeVelocity(const Vector3d& r, int other, const Vector3d& r_other,
                            const Vector3d& v_other) const;
  Vector3d RowVelocity(size_t i) const;
  void Apply(const Vector3d& r, int other, const Vector3d& r_other, const Vector3d& impulse);
  void ApplyRow(size_t i, const Vector3d& impulse);
  // Friction at point i within `limit` (its accumulated impulse clamped).
  void Friction(size_t i, double limit);
  // The velocity pass; sets each contact's impulse_W.
  void SolveVelocities();
  // The position pass; moves the body.
  void SolvePositions(const MassProperties& body);

  ContactSolverOptions options_;
  // The body and contacts of the Solve running.
  FreeBodyState* state_ = nullptr;
  std::span<SolverContact> contacts_;
  double inverse_mass_ = 0;
  Matrix3d inverse_I_W_ = Matrix3d::Zero();
  std::vector<Row> rows_;
  std::vector<int> order_;  // non-tool rows: bodies, then fixed
  std::vector<Patch> patches_;
  std::vector<Other> others_;
};

}  // namespace hs
