#pragma once
// Test helper: two SideContacts compared field by field.

#include <gtest/gtest.h>

#include "common/contact/contact_set.h"

namespace hs::testing_contacts {

inline void ExpectSameSide(const SideContact& got, const SideContact& want) {
  EXPECT_EQ(got.kind, want.kind);
  EXPECT_EQ(got.vertices, want.vertices);
  EXPECT_EQ(got.edges, want.edges);
  EXPECT_EQ(got.faces, want.faces);
}

}  // namespace hs::testing_contacts
