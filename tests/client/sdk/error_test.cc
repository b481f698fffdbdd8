#include "haptics/error.h"

#include <gtest/gtest.h>

#include "absl/status/status.h"

namespace haptics {
namespace {

TEST(ErrorTest, CodeNamesAreGrpcs) {
  // Every code's name is the one Abseil (and gRPC) give the same number.
  for (int c = 0; c <= 16; ++c) {
    EXPECT_EQ(CodeName(static_cast<Code>(c)),
              absl::StatusCodeToString(static_cast<absl::StatusCode>(c)));
  }
  EXPECT_STREQ(CodeName(static_cast<Code>(99)), "UNKNOWN");
}

TEST(ErrorTest, ToStringNamesTheCodeThenTheMessage) {
  // "CODE: message", and "OK" for no error.
  EXPECT_EQ((Error{Code::kNotFound, "no scene 'x'"}).ToString(), "NOT_FOUND: no scene 'x'");
  EXPECT_EQ(Error{}.ToString(), "OK");
}

TEST(ErrorTest, ResultWithoutAValueIsNeverOk) {
  // A Result holds its value, or an error; an OK error counts as UNKNOWN.
  Result<int> value(7);
  ASSERT_TRUE(value.ok());
  EXPECT_EQ(*value, 7);
  EXPECT_TRUE(value.error().ok());
  Result<int> failed(Error{Code::kUnavailable, "gone"});
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().code, Code::kUnavailable);
  Result<int> odd(Error{});
  EXPECT_FALSE(odd.ok());
  EXPECT_EQ(odd.error().code, Code::kUnknown);
}

}  // namespace
}  // namespace haptics
