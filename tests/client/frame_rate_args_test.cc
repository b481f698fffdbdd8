#include "client/frame_rate_args.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace hs::cli {
namespace {

// Parses `args` (after the program name) into a command with only
// --frame-rate-hz, starting from `hz`.
double Parsed(std::vector<std::string> args, double hz = 0) {
  CLI::App app;
  AddFrameRateOption(app, hz);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return hz;
}

// The bounds are inclusive; anything not finite, or past them, is refused
// with a message naming the flag.
TEST(FrameRateArgsTest, Bounds) {
  EXPECT_TRUE(CheckFrameRate(kMinFrameRateHz).ok());
  EXPECT_TRUE(CheckFrameRate(1000).ok());
  EXPECT_TRUE(CheckFrameRate(kMaxFrameRateHz).ok());
  for (const double bad :
       {0.0, 0.999, -1.0, std::nextafter(kMaxFrameRateHz, 1e9),
        std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    const absl::Status status = CheckFrameRate(bad);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(status.message().find("--frame-rate-hz"), std::string::npos) << status;
  }
}

// The flag fills the value when given and leaves it alone otherwise; a
// value out of bounds, not finite or not a number is a command-line error.
TEST(FrameRateArgsTest, Flag) {
  EXPECT_EQ(Parsed({"--frame-rate-hz", "250"}), 250);
  EXPECT_EQ(Parsed({}, 7), 7);
  for (const char* bad : {"0", "100001", "nan", "inf", "-5", "fast"}) {
    EXPECT_THROW(Parsed({"--frame-rate-hz", bad}), CLI::ValidationError) << bad;
  }
  try {
    Parsed({"--frame-rate-hz", "nan"});
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("from 1 to 100000"), std::string::npos) << e.what();
  }
}

// A rate asked for goes out in the open message; none (0) leaves the
// field unset, the server's own rate.
TEST(FrameRateArgsTest, OpenMessage) {
  haptics::v1::InteractRequest::Open open;
  SetFrameRate(open, 0);
  EXPECT_EQ(open.frame_rate_hz(), 0);
  SetFrameRate(open, 500);
  EXPECT_EQ(open.frame_rate_hz(), 500);
}

}  // namespace
}  // namespace hs::cli
