#include "client/sdk/device_link.h"

#include <gtest/gtest.h>

namespace hs::sdk {
namespace {

TEST(DeviceLinkTest, RetriesWhatMayPass) {
  // A stream ended by the link or the server's state is opened again; one
  // the server refused for good (taken over, a token or request refused),
  // or ended as asked, is not.
  for (haptics::Code code :
       {haptics::Code::kUnavailable, haptics::Code::kDeadlineExceeded, haptics::Code::kNotFound,
        haptics::Code::kFailedPrecondition, haptics::Code::kResourceExhausted,
        haptics::Code::kInternal, haptics::Code::kCancelled, haptics::Code::kUnknown}) {
    EXPECT_TRUE(Retried(code)) << haptics::CodeName(code);
  }
  for (haptics::Code code : {haptics::Code::kOk, haptics::Code::kAborted,
                             haptics::Code::kInvalidArgument, haptics::Code::kPermissionDenied,
                             haptics::Code::kUnauthenticated, haptics::Code::kUnimplemented}) {
    EXPECT_FALSE(Retried(code)) << haptics::CodeName(code);
  }
}

}  // namespace
}  // namespace hs::sdk
