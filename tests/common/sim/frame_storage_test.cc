// CopyFrame and the spare contact sets. A binary of its own: it links the
// counting global operator new.

#include "common/sim/frame_storage.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/common/allocation_counter.h"
#include "tests/common/contact/expect_same_side.h"

namespace hs {
namespace {

using testing_contacts::ExpectSameSide;

// A frame of `tools` tools, each with up to `most_pairs` contacts of up to
// `most_features` features and points, every field drawn from `rng`.
StepFrame RandomFrame(std::mt19937& rng, int tools, int most_pairs, int most_features) {
  std::uniform_int_distribution<int> pairs(0, most_pairs), features(0, most_features);
  std::uniform_real_distribution<double> u(-1, 1);
  StepFrame frame;
  frame.step = rng() % 1000;
  frame.time_s = u(rng);
  for (int t = 0; t < tools; ++t) {
    ToolFrame& tool = frame.tools.emplace_back();
    tool.tool = t;
    tool.force_W = Vector3d(u(rng), u(rng), u(rng));
    tool.substeps = 1 + rng() % 3;
    for (int p = pairs(rng); p > 0; --p) {
      PairContact& pair = tool.contacts.emplace_back();
      pair.object = rng() % 50;
      pair.substep = 1 + rng() % 3;
      ContactSet& c = pair.contact;
      c.colliding = true;
      c.depth_m = u(rng);
      c.normal_W = Vector3d(u(rng), u(rng), u(rng));
      for (SideContact* side : {&c.moving, &c.fixed}) {
        side->kind = FeatureKind::kFace;
        for (int i = features(rng); i > 0; --i) side->vertices.push_back(rng() % 100);
        for (int i = features(rng); i > 0; --i) side->edges.push_back(rng() % 100);
        for (int i = features(rng); i > 0; --i) side->faces.push_back(rng() % 100);
      }
      for (int i = features(rng); i > 0; --i) {
        c.points.push_back({Vector3d(u(rng), u(rng), u(rng)),
                            {FeatureKind::kVertex, static_cast<int32_t>(rng() % 100)},
                            {FeatureKind::kFace, static_cast<int32_t>(rng() % 100)}});
      }
    }
  }
  return frame;
}

// Field by field, what RandomFrame fills.
void ExpectSameFrame(const StepFrame& a, const StepFrame& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time_s, b.time_s);
  ASSERT_EQ(a.tools.size(), b.tools.size());
  for (size_t t = 0; t < a.tools.size(); ++t) {
    const ToolFrame &x = a.tools[t], &y = b.tools[t];
    EXPECT_EQ(x.tool, y.tool);
    EXPECT_EQ(x.force_W, y.force_W);
    EXPECT_EQ(x.substeps, y.substeps);
    ASSERT_EQ(x.contacts.size(), y.contacts.size());
    for (size_t p = 0; p < x.contacts.size(); ++p) {
      const PairContact &m = x.contacts[p], &n = y.contacts[p];
      EXPECT_EQ(m.object, n.object);
      EXPECT_EQ(m.substep, n.substep);
      EXPECT_EQ(m.contact.colliding, n.contact.colliding);
      EXPECT_EQ(m.contact.depth_m, n.contact.depth_m);
      EXPECT_EQ(m.contact.normal_W, n.contact.normal_W);
      ExpectSameSide(m.contact.moving, n.contact.moving);
      ExpectSameSide(m.contact.fixed, n.contact.fixed);
      ASSERT_EQ(m.contact.points.size(), n.contact.points.size());
      for (size_t i = 0; i < m.contact.points.size(); ++i) {
        EXPECT_EQ(m.contact.points[i].p_WC, n.contact.points[i].p_WC);
        EXPECT_EQ(m.contact.points[i].moving, n.contact.points[i].moving);
        EXPECT_EQ(m.contact.points[i].fixed, n.contact.points[i].fixed);
      }
    }
  }
}

// Copies over one target of frames that grow and shrink in tools, pairs
// and features give the source every time.
TEST(FrameStorageTest, CopyGivesTheSource) {
  std::mt19937 rng(9);
  FrameCopyStorage storage;
  StepFrame to;
  for (int k = 0; k < 200; ++k) {
    const StepFrame from = RandomFrame(rng, 1 + rng() % 3, 4, 6);
    CopyFrame(from, to, storage);
    SCOPED_TRACE(k);
    ExpectSameFrame(to, from);
  }
}

// Once the largest frame has been copied into the target, copies of any
// frame no larger allocate nothing, however the pairs come and go.
TEST(FrameStorageTest, CopiesAfterTheLargestAllocateNothing) {
  std::mt19937 rng(10);
  std::vector<StepFrame> frames;
  for (int k = 0; k < 50; ++k) frames.push_back(RandomFrame(rng, 2, 5, 8));
  StepFrame largest = RandomFrame(rng, 2, 0, 0);
  for (ToolFrame& tool : largest.tools) {
    tool.contacts.resize(5);
    for (PairContact& pair : tool.contacts) {
      for (SideContact* side : {&pair.contact.moving, &pair.contact.fixed}) {
        side->vertices.assign(8, 1);
        side->edges.assign(8, 2);
        side->faces.assign(8, 3);
      }
      pair.contact.points.resize(8);
    }
  }
  FrameCopyStorage storage;
  StepFrame to;
  CopyFrame(largest, to, storage);
  for (const StepFrame& from : frames) CopyFrame(from, to, storage);  // the spares fill
  CopyFrame(largest, to, storage);
  const long before = AllocationCount();
  for (const StepFrame& from : frames) CopyFrame(from, to, storage);
  EXPECT_EQ(AllocationCount() - before, 0);
  ExpectSameFrame(to, frames.back());
}

// A pair added after a clear takes a spare contact set: cleared, its
// vectors' storage kept; with no spare it is a fresh one.
TEST(FrameStorageTest, ClearedPairsAreReusedCleared) {
  std::mt19937 rng(11);
  StepFrame frame = RandomFrame(rng, 1, 0, 0);
  std::vector<PairContact>& contacts = frame.tools[0].contacts;
  PairContact& first = contacts.emplace_back();
  first.contact.colliding = true;
  first.contact.depth_m = 0.5;
  first.contact.moving.vertices.assign(20, 4);
  first.contact.points.resize(30);
  std::vector<ContactSet> spare;
  ClearPairContacts(contacts, spare);
  EXPECT_TRUE(contacts.empty());
  ASSERT_EQ(spare.size(), 1u);
  const PairContact& reused = AddPairContact(contacts, spare);
  EXPECT_TRUE(spare.empty());
  EXPECT_FALSE(reused.contact.colliding);
  EXPECT_EQ(reused.contact.depth_m, 0);
  EXPECT_TRUE(reused.contact.moving.vertices.empty());
  EXPECT_TRUE(reused.contact.points.empty());
  EXPECT_GE(reused.contact.moving.vertices.capacity(), 20u);
  EXPECT_GE(reused.contact.points.capacity(), 30u);
  const PairContact& fresh = AddPairContact(contacts, spare);
  EXPECT_FALSE(fresh.contact.colliding);
  EXPECT_EQ(contacts.size(), 2u);
}

}  // namespace
}  // namespace hs
