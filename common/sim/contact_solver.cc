#include "common/sim/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Two unit tangents completing the unit normal n to a right-handed basis.
void Tangents(const Vector3d& n, Vector3d& t1, Vector3d& t2) {
  // The world axis least along n keeps the cross product well conditioned.
  const Vector3d axis = std::abs(n.x()) < 0.57735   ? Vector3d::UnitX()
                        : std::abs(n.y()) < 0.57735 ? Vector3d::UnitY()
                                                    : Vector3d::UnitZ();
  t1 = n.cross(axis).normalized();
  t2 = n.cross(t1);
}

Matrix3d InverseInertiaW(const MassProperties& mass, const FreeBodyState& state) {
  const Matrix3d R = state.X_WO.linear();
  return R * mass.I_C.inverse() * R.transpose();
}

// Turns `state` by the small rotation `dtheta` (world frame, radians) about
// the centre of mass and moves the centre of mass by `dx`.
void Displace(const MassProperties& mass, const Vector3d& dx, const Vector3d& dtheta,
              FreeBodyState& state) {
  const Vector3d c = CentreOfMass(mass, state) + dx;
  const double angle = dtheta.norm();
  if (angle > 0) {
    Eigen::Quaterniond q(state.X_WO.linear());
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle)) * q;
    q.normalize();
    state.X_WO.linear() = q.toRotationMatrix();
  }
  state.X_WO.translation() = c - state.X_WO.linear() * mass.p_OC;
}

}  // namespace

double ContactSolver::Response(const Vector3d& u, const Vector3d& r, int other,
                               const Vector3d& r_other) const {
  double k = inverse_mass_ + u.dot((inverse_I_W_ * r.cross(u)).cross(r));
  if (other >= 0) {
    const Other& o = others_[other];
    k += 1 / o.mass->mass_kg + u.dot((o.inverse_I_W * r_other.cross(u)).cross(r_other));
  }
  return k;
}

int ContactSolver::OtherIndex(const SolverContact& contact) {
  // Others are few: a linear search finds a body met before.
  for (size_t o = 0; o < others_.size(); ++o) {
    if (others_[o].state == contact.other.state) return static_cast<int>(o);
  }
  Other other;
  other.mass = contact.other.mass;
  other.state = contact.other.state;
  other.c = CentreOfMass(*other.mass, *other.state);
  // The other takes the impulses through its centre of mass: its turn is
  // left to its own contacts, which this problem does not hold (a body
  // landing off-centre on one resting on the floor would otherwise spin
  // both, as if nothing held the lower one).
  other.inverse_I_W = Matrix3d::Zero();
  others_.push_back(other);
  return static_cast<int>(others_.size()) - 1;
}

void ContactSolver::SetUpRows(const Vector3d& c, double h_s) {
  for (size_t i = 0; i < contacts_.size(); ++i) {
    const SolverContact& contact = contacts_[i];
    Row& row = rows_[i];
    row = Row{};
    row.r = contact.p_WC - c;
    if (contact.side == ContactSide::kBody) {
      row.other = OtherIndex(contact);
      row.r_other = contact.p_WC - others_[row.other].c;
    }
    Tangents(contact.normal_W, row.t1, row.t2);
    row.k_n = Response(contact.normal_W, row.r, row.other, row.r_other);
    row.k_push = Response(contact.normal_W, row.r, -1, Vector3d::Zero());
    row.k_t1 = Response(row.t1, row.r, row.other, row.r_other);
    row.k_t2 = Response(row.t2, row.r, row.other, row.r_other);
    row.closing = std::max(0.0, -contact.depth_m) / h_s;
    if (contact.side == ContactSide::kTool) {
      // A tool's points that follow one another with one tag and one
      // normal are one patch.
      const bool same = !patches_.empty() && i > 0 && contacts_[i - 1].side == ContactSide::kTool &&
                        contacts_[i - 1].tag == contact.tag &&
                        contacts_[i - 1].normal_W == contact.normal_W;
      if (!same) {
        Patch patch;
        patch.first = static_cast<int>(i);
        patch.n = contact.normal_W;
        patch.v_other = contact.v_other_W;
        patch.depth = contact.depth_m;
        patch.max_push = std::max(0.0, contact.max_push_m);
        patches_.push_back(patch);
      }
      Patch& patch = patches_.back();
      ++patch.count;
      patch.lo += std::max(0.0, contact.grip_impulse);
      patch.depth = std::max(patch.depth, contact.depth_m);
      row.patch = static_cast<int>(patches_.size()) - 1;
    }
  }
  for (Patch& patch : patches_) {
    // The middle of the points' extent on the face, not their mean: the
    // query may report a point twice (two feature pairs) or add points
    // where the faces' triangulations cross, which would shift a mean.
    Vector3d t1, t2;
    Tangents(patch.n, t1, t2);
    Vector3d lo = Vector3d::Constant(kInfinity), hi = -lo;
    for (int k = 0; k < patch.count; ++k) {
      const Vector3d& r = rows_[static_cast<size_t>(patch.first + k)].r;
      const Vector3d local(r.dot(t1), r.dot(t2), r.dot(patch.n));
      lo = lo.cwiseMin(local);
      hi = hi.cwiseMax(local);
    }
    const Vector3d middle = (lo + hi) / 2;
    patch.r = middle.x() * t1 + middle.y() * t2 + middle.z() * patch.n;
    patch.k_n = Response(patch.n, patch.r, -1, Vector3d::Zero());
    patch.closing = std::max(0.0, -patch.depth) / h_s;
  }
  // Bodies, then fixed objects: the last word in each sweep goes to what
  // must not give way (tools' patches come first of all).
  for (const ContactSide side : {ContactSide::kBody, ContactSide::kFixed}) {
    for (size_t i = 0; i < contacts_.size(); ++i) {
      if (contacts_[i].side == side) order_.push_back(static_cast<int>(i));
    }
  }
}

Vector3d ContactSolver::RelativeVelocity(const Vector3d& r, int other, const Vector3d& r_other,
                                         const Vector3d& v_other) const {
  Vector3d v = state_->v_W + state_->w_W.cross(r);
  if (other >= 0) {
    const FreeBodyState& o = *others_[other].state;
    v -= o.v_W + o.w_W.cross(r_other);
  } else {
    v -= v_other;
  }
  return v;
}

Vector3d ContactSolver::RowVelocity(size_t i) const {
  const Row& row = rows_[i];
  return RelativeVelocity(row.r, row.other, row.r_other, contacts_[i].v_other_W);
}

void ContactSolver::Apply(const Vector3d& r, int other, const Vector3d& r_other,
                          const Vector3d& impulse) {
  state_->v_W += inverse_mass_ * impulse;
  state_->w_W += inverse_I_W_ * r.cross(impulse);
  if (other >= 0) {
    const Other& o = others_[other];
    o.state->v_W -= impulse / o.mass->mass_kg;
    o.state->w_W -= o.inverse_I_W * r_other.cross(impulse);
  }
}

void ContactSolver::ApplyRow(size_t i, const Vector3d& impulse) {
  const Row& row = rows_[i];
  Apply(row.r, row.other, row.r_other, impulse);
}

void ContactSolver::Friction(size_t i, double limit) {
  Row& row = rows_[i];
  const Vector3d v = RowVelocity(i);
  double t1 = row.tangent1 - row.t1.dot(v) / row.k_t1;
  double t2 = row.tangent2 - row.t2.dot(v) / row.k_t2;
  const double length = std::hypot(t1, t2);
  if (length > limit) {
    const double scale = length > 0 ? limit / length : 0.0;
    t1 *= scale;
    t2 *= scale;
  }
  ApplyRow(i, (t1 - row.tangent1) * row.t1 + (t2 - row.tangent2) * row.t2);
  row.tangent1 = t1;
  row.tangent2 = t2;
}

void ContactSolver::SolveVelocities() {
  // Bounds, from the velocities at the start: a tool's patch presses with
  // at least its grip, and stops the approach at its centroid at most as
  // far as a hard contact there would alone. The grips act at once.
  for (Patch& patch : patches_) {
    const double approach =
        std::max(0.0, -patch.n.dot(RelativeVelocity(patch.r, -1, Vector3d::Zero(), patch.v_other)) -
                          patch.closing);
    patch.hi = patch.lo + approach / patch.k_n;
    patch.normal = patch.lo;
  }
  for (const int index : order_) {
    Row& row = rows_[static_cast<size_t>(index)];
    row.lo = 0;
    row.hi = kInfinity;
  }
  for (const Patch& patch : patches_) {
    if (patch.lo > 0) Apply(patch.r, -1, Vector3d::Zero(), patch.lo * patch.n);
  }
  // Friction at each point within its limit; the normal row after it has
  // the last word on the approach.
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    for (Patch& patch : patches_) {
      const double share = patch.normal / static_cast<double>(patch.count);
      for (int k = 0; k < patch.count; ++k) {
        const size_t i = static_cast<size_t>(patch.first + k);
        if (contacts_[i].friction > 0) Friction(i, contacts_[i].friction * share);
      }
      const double vn =
          patch.n.dot(RelativeVelocity(patch.r, -1, Vector3d::Zero(), patch.v_other)) +
          patch.closing;
      const double normal = std::clamp(patch.normal - vn / patch.k_n, patch.lo, patch.hi);
      Apply(patch.r, -1, Vector3d::Zero(), (normal - patch.normal) * patch.n);
      patch.normal = normal;
    }
    for (const int index : order_) {
      const size_t i = static_cast<size_t>(index);
      const SolverContact& contact = contacts_[i];
      Row& row = rows_[i];
      if (contact.friction > 0) Friction(i, contact.friction * row.normal);
      const double vn = contact.normal_W.dot(RowVelocity(i)) + row.closing;
      const double normal = std::clamp(row.normal - vn / row.k_n, row.lo, row.hi);
      ApplyRow(i, (normal - row.normal) * contact.normal_W);
      row.normal = normal;
    }
  }
  for (size_t i = 0; i < contacts_.size(); ++i) {
    const Row& row = rows_[i];
    const double normal =
        row.patch >= 0 ? patches_[row.patch].normal / patches_[row.patch].count : row.normal;
    contacts_[i].impulse_W =
        normal * contacts_[i].normal_W + row.tangent1 * row.t1 + row.tangent2 * row.t2;
  }
}

void ContactSolver::SolvePositions(const MassProperties& body) {
  // Pseudo-impulses (kg*m) that move, not speed up, the body out along
  // each contact's own normal. A tool's patch pushes the body at most its
  // own advance; fixed objects and bodies push the depth, capped.
  Vector3d dx = Vector3d::Zero(), dtheta = Vector3d::Zero();
  for (Patch& patch : patches_) {
    patch.push_hi = patch.max_push / patch.k_n;
    patch.push = 0;
  }
  for (const int index : order_) {
    const size_t i = static_cast<size_t>(index);
    Row& row = rows_[i];
    row.push_target = std::min(contacts_[i].depth_m, std::max(0.0, contacts_[i].max_push_m));
    row.push = 0;
  }
  auto pushed = [&](const Vector3d& n, const Vector3d& r) { return n.dot(dx + dtheta.cross(r)); };
  auto push_by = [&](const Vector3d& r, const Vector3d& p) {
    dx += inverse_mass_ * p;
    dtheta += inverse_I_W_ * r.cross(p);
  };
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    for (Patch& patch : patches_) {
      if (patch.push_hi <= 0) continue;
      const double push = std::clamp(
          patch.push + (patch.depth - pushed(patch.n, patch.r)) / patch.k_n, 0.0, patch.push_hi);
      push_by(patch.r, (push - patch.push) * patch.n);
      patch.push = push;
    }
    for (const int index : order_) {
      const size_t i = static_cast<size_t>(index);
      Row& row = rows_[i];
      const Vector3d& n = contacts_[i].normal_W;
      // The body moves out of another body on its own: the other was
      // placed by its own contacts (a stack's lower cubes rest on the floor
      // and are not pressed into it from above).
      const double push =
          std::max(0.0, row.push + (row.push_target - pushed(n, row.r)) / row.k_push);
      push_by(row.r, (push - row.push) * n);
      row.push = push;
    }
  }
  Displace(body, dx, dtheta, *state_);
}

void ContactSolver::Solve(const MassProperties& body, FreeBodyState& state,
                          std::span<SolverContact> contacts, double h_s) {
  if (contacts.empty()) return;
  rows_.resize(contacts.size());
  order_.clear();
  others_.clear();
  patches_.clear();
  state_ = &state;
  contacts_ = contacts;
  inverse_mass_ = 1 / body.mass_kg;
  inverse_I_W_ = InverseInertiaW(body, state);
  SetUpRows(CentreOfMass(body, state), h_s);
  SolveVelocities();
  SolvePositions(body);
  state_ = nullptr;
  contacts_ = {};
}

}  // namespace hs
