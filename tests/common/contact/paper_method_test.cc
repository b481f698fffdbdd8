#include <gtest/gtest.h>

#include "common/contact/contact_query.h"

namespace hs {
namespace {

// Placeholder: replaced by the paper method's tests.
TEST(PaperMethodTest, Placeholder) { EXPECT_TRUE(true); }

}  // namespace
}  // namespace hs
