// The contact solver (contact_solver.h) on hand-built contacts of a 1 m,
// 1 kg cube: its answers against impulses and moves worked out by hand.
#include "common/sim/contact_solver.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace hs {
namespace {

// A 1 m cube of 1 kg: I = m s^2 / 6 about each axis.
MassProperties UnitCube() {
  MassProperties m;
  m.mass_kg = 1;
  m.I_C = Matrix3d::Identity() / 6;
  return m;
}

// The four corners of the unit cube's face on the side `sign` of `axis`
// (centre at the origin), as contacts of `side` with the normal pointing
// into the cube from that face's outside.
std::vector<SolverContact> FaceContacts(int axis, double sign, ContactSide side, int tag = -1) {
  std::vector<SolverContact> out;
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  for (const double a : {-0.5, 0.5}) {
    for (const double b : {-0.5, 0.5}) {
      SolverContact c;
      c.side = side;
      c.p_WC[axis] = 0.5 * sign;
      c.p_WC[u] = a;
      c.p_WC[w] = b;
      c.normal_W = Vector3d::Zero();
      c.normal_W[axis] = -sign;
      c.tag = tag;
      out.push_back(c);
    }
  }
  return out;
}

Vector3d SumImpulse(const std::vector<SolverContact>& contacts, int tag) {
  Vector3d sum = Vector3d::Zero();
  for (const SolverContact& c : contacts) {
    if (c.tag == tag) sum += c.impulse_W;
  }
  return sum;
}

// The sub-step, seconds.
constexpr double kH = 1e-3;

// Converged Gauss-Seidel leaves residuals far below these: 1e-9 of the
// 1 m/s and 1 m scales of the cases.
constexpr double kTight = 1e-9;

// A cube falling at 1 m/s onto a floor under its bottom face (four corner
// points, 1 cm deep) stops (momentum m v = 1 N*s goes to the floor), is
// moved up 1 cm, and does not turn.
TEST(ContactSolverTest, FloorStopsFallAndPushesOutAlongNormal) {
  FreeBodyState s;
  s.v_W = Vector3d(0, 0, -1);
  std::vector<SolverContact> contacts = FaceContacts(2, -1, ContactSide::kFixed);
  for (SolverContact& c : contacts) {
    c.depth_m = 0.01;
    c.max_push_m = 1;
  }
  ContactSolver solver;
  solver.Solve(UnitCube(), s, contacts, kH);
  EXPECT_LT(s.v_W.norm(), kTight);
  EXPECT_LT(s.w_W.norm(), kTight);
  EXPECT_NEAR(SumImpulse(contacts, -1).z(), 1, kTight);
  EXPECT_NEAR(s.X_WO.translation().z(), 0.01, kTight);
  EXPECT_LT(s.X_WO.translation().head<2>().norm(), kTight);
  EXPECT_TRUE(s.X_WO.linear().isIdentity(kTight));
}

// A fixed object's push is capped: a 0.5 m depth (a wrong measure) with a
// 1 mm cap moves the body 1 mm, not 0.5 m.
TEST(ContactSolverTest, FixedPushCapped) {
  FreeBodyState s;
  std::vector<SolverContact> contacts = FaceContacts(0, -1, ContactSide::kFixed);
  for (SolverContact& c : contacts) {
    c.depth_m = 0.5;
    c.max_push_m = 0.001;
  }
  ContactSolver().Solve(UnitCube(), s, contacts, kH);
  EXPECT_NEAR(s.X_WO.translation().x(), 0.001, kTight);
}

// Friction at a point under the centre of mass removes sliding up to mu
// times the normal impulse: v = (1, 0, -0.5), mu = 0.4 give normal 0.5 N*s
// and friction 0.2 N*s, so v = (0.8, 0, 0); a body leaving takes nothing.
TEST(ContactSolverTest, FrictionLimitedByCone) {
  FreeBodyState s;
  s.v_W = Vector3d(1, 0, -0.5);
  std::array<SolverContact, 1> contact;
  contact[0].p_WC = Vector3d::Zero();
  contact[0].friction = 0.4;
  ContactSolver solver;
  solver.Solve(UnitCube(), s, contact, kH);
  EXPECT_NEAR(s.v_W.x(), 0.8, kTight);
  EXPECT_NEAR(s.v_W.z(), 0, kTight);
  EXPECT_NEAR(contact[0].impulse_W.x(), -0.2, kTight);
  EXPECT_NEAR(contact[0].impulse_W.z(), 0.5, kTight);
  s.v_W.z() = 0.1;
  const Vector3d leaving = s.v_W;
  solver.Solve(UnitCube(), s, contact, kH);
  EXPECT_EQ(contact[0].impulse_W, Vector3d::Zero());
  EXPECT_EQ(s.v_W, leaving);
}

// Two equal bodies meeting head on stop each other (restitution 0), with
// equal and opposite impulses (momentum kept); the body solved moves out
// of the other, 1 cm deep, by itself: the other stays where its own
// contacts put it.
TEST(ContactSolverTest, TwoBodiesShareImpulseBodySolvedMovesOut) {
  FreeBodyState a, b;
  a.v_W = Vector3d(1, 0, 0);
  b.v_W = Vector3d(-1, 0, 0);
  b.X_WO.translation() = Vector3d(0.99, 0, 0);
  const MassProperties m = UnitCube();
  std::vector<SolverContact> contacts = FaceContacts(0, 1, ContactSide::kBody);
  for (SolverContact& c : contacts) {
    c.other = {&m, &b};
    c.depth_m = 0.01;
    c.max_push_m = 1;
  }
  ContactSolver().Solve(m, a, contacts, kH);
  EXPECT_LT(a.v_W.norm(), kTight);
  EXPECT_LT(b.v_W.norm(), kTight);
  EXPECT_NEAR(SumImpulse(contacts, -1).x(), -1, kTight);  // a took -1, b +1
  EXPECT_NEAR(a.X_WO.translation().x(), -0.01, kTight);
  EXPECT_EQ(b.X_WO.translation().x(), 0.99);
}

// Two tools pinch the cube from the x sides, each with a grip of 1 N*s and
// friction 0.5, against one step of gravity (v_z = -g h): each carries
// half the weight's impulse, m g h / 2, whichever is solved first, and
// presses with its grip, equal and opposite.
TEST(ContactSolverTest, SymmetricPinchSharesWeightEvenly) {
  const double g_h = 9.81e-3;
  for (const bool left_first : {true, false}) {
    FreeBodyState s;
    s.v_W = Vector3d(0, 0, -g_h);
    std::vector<SolverContact> left = FaceContacts(0, -1, ContactSide::kTool, 1);
    std::vector<SolverContact> right = FaceContacts(0, 1, ContactSide::kTool, 2);
    std::vector<SolverContact> contacts = left_first ? left : right;
    contacts.insert(contacts.end(), (left_first ? right : left).begin(),
                    (left_first ? right : left).end());
    for (SolverContact& c : contacts) {
      c.friction = 0.5;
      c.grip_impulse = 0.25;
    }
    ContactSolver().Solve(UnitCube(), s, contacts, kH);
    EXPECT_LT(s.v_W.norm(), kTight);
    EXPECT_LT(s.w_W.norm(), kTight);
    // The sweeps leave about 1e-9 of the share unsolved.
    EXPECT_NEAR(SumImpulse(contacts, 1).z(), g_h / 2, 1e-7 * g_h);
    EXPECT_NEAR(SumImpulse(contacts, 2).z(), g_h / 2, 1e-7 * g_h);
    EXPECT_NEAR(SumImpulse(contacts, 1).x(), 1, kTight);
    EXPECT_NEAR(SumImpulse(contacts, 2).x(), -1, kTight);
  }
}

// Two tools closing on the cube at 1 m/s each, with no grip: a hard
// contact alone would stop each; together they press with at most that
// (per point 1 m/s over its response 1/m + |r x n|^2 / I = 4 / kg, so
// 0.25 N*s), the cube stays still, and neither pushes it out further than
// it advanced (1 mm), so the cube does not move.
TEST(ContactSolverTest, ClosingToolsPressBoundedAndCancel) {
  FreeBodyState s;
  std::vector<SolverContact> contacts = FaceContacts(0, -1, ContactSide::kTool, 1);
  for (SolverContact& c : contacts) c.v_other_W = Vector3d(1, 0, 0);
  for (SolverContact& c : FaceContacts(0, 1, ContactSide::kTool, 2)) {
    c.v_other_W = Vector3d(-1, 0, 0);
    contacts.push_back(c);
  }
  for (SolverContact& c : contacts) {
    c.depth_m = 0.003;
    c.max_push_m = 0.001;
  }
  ContactSolver().Solve(UnitCube(), s, contacts, kH);
  for (const SolverContact& c : contacts) EXPECT_NEAR(c.impulse_W.norm(), 0.25, kTight);
  EXPECT_LT(s.v_W.norm(), kTight);
  EXPECT_LT(s.X_WO.translation().norm(), kTight);
}

// A tool pushing the cube down into a fixed floor (tool 2 mm in, advanced
// 1 mm, approaching at 1 m/s) cannot drive it in: the floor has the last
// word on both passes, and the tool feels minus what the cube took.
TEST(ContactSolverTest, FixedObjectWinsOverTool) {
  FreeBodyState s;
  std::vector<SolverContact> contacts = FaceContacts(2, 1, ContactSide::kTool, 1);
  for (SolverContact& c : contacts) {
    c.v_other_W = Vector3d(0, 0, -1);
    c.depth_m = 0.002;
    c.max_push_m = 0.001;
    c.grip_impulse = 0.01;
  }
  for (SolverContact& c : FaceContacts(2, -1, ContactSide::kFixed, 0)) {
    c.max_push_m = 0.001;
    contacts.push_back(c);
  }
  ContactSolver().Solve(UnitCube(), s, contacts, kH);
  EXPECT_GE(s.v_W.z(), -kTight);
  EXPECT_GE(s.X_WO.translation().z(), -kTight);
  // The floor took what the tool gave: the cube's momentum did not change.
  EXPECT_LT((SumImpulse(contacts, 0) + SumImpulse(contacts, 1)).norm(), kTight);
  EXPECT_LT(SumImpulse(contacts, 1).z(), 0);
}

// A tool alone pushes the cube out of it at most as far as it advanced:
// 5 mm deep, 1 mm advance: the cube moves 1 mm.
TEST(ContactSolverTest, ToolPushBoundedByItsAdvance) {
  FreeBodyState s;
  std::vector<SolverContact> contacts = FaceContacts(0, -1, ContactSide::kTool, 1);
  for (SolverContact& c : contacts) {
    c.depth_m = 0.005;
    c.max_push_m = 0.001;
  }
  ContactSolver().Solve(UnitCube(), s, contacts, kH);
  EXPECT_NEAR(s.X_WO.translation().x(), 0.001, kTight);
  EXPECT_LT(s.X_WO.translation().tail<2>().norm(), kTight);
}

}  // namespace
}  // namespace hs
