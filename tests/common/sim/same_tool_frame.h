#pragma once
// Test helper: two step frames' tools the same to the bit (the thread
// tests).

#include <gtest/gtest.h>

#include <cstring>

#include "common/sim/step_frame.h"

namespace hs {

inline void ExpectSameToolFrame(const ToolFrame& x, const ToolFrame& y) {
  EXPECT_EQ(std::memcmp(x.force_W.data(), y.force_W.data(), sizeof(double) * 3), 0);
  EXPECT_EQ(std::memcmp(x.torque_W.data(), y.torque_W.data(), sizeof(double) * 3), 0);
  EXPECT_TRUE(x.X_WP.matrix() == y.X_WP.matrix());
  EXPECT_EQ(x.touched_tool, y.touched_tool);
  ASSERT_EQ(x.contacts.size(), y.contacts.size());
  for (size_t k = 0; k < x.contacts.size(); ++k) {
    const ContactSet& a = x.contacts[k].contact;
    const ContactSet& b = y.contacts[k].contact;
    EXPECT_EQ(x.contacts[k].object, y.contacts[k].object);
    EXPECT_EQ(std::memcmp(&a.depth_m, &b.depth_m, sizeof(double)), 0);
    EXPECT_EQ(a.fixed.faces, b.fixed.faces);
    EXPECT_EQ(a.moving.vertices, b.moving.vertices);
  }
}

inline void ExpectSameToolFrames(const StepFrame& a, const StepFrame& b) {
  ASSERT_EQ(a.tools.size(), b.tools.size());
  for (size_t t = 0; t < a.tools.size(); ++t) ExpectSameToolFrame(a.tools[t], b.tools[t]);
}

}  // namespace hs
