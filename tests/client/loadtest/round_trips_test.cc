#include "client/loadtest/round_trips.h"

#include <gtest/gtest.h>

#include <vector>

namespace hs::cli {
namespace {

// An answer covers every message sent up to its sequence not answered
// before, once each; an answer to a message not yet sent covers only
// those sent.
TEST(RoundTripsTest, AnswersCoverEarlierMessagesOnce) {
  RoundTrips trips(5);
  trips.MarkSent(1);
  trips.MarkSent(2);
  trips.MarkAnswered(4);  // only 1 and 2 are out
  EXPECT_EQ(trips.sent(), 2u);
  EXPECT_EQ(trips.answered(), 2u);
  trips.MarkAnswered(2);  // nothing new
  EXPECT_EQ(trips.rtt_ms().size(), 2u);
  trips.MarkSent(3);
  trips.MarkSent(4);
  trips.MarkAnswered(4);
  EXPECT_EQ(trips.answered(), 4u);
  ASSERT_EQ(trips.rtt_ms().size(), 4u);
  for (const double ms : trips.rtt_ms()) EXPECT_GE(ms, 0);
  // An earlier message waited at least as long as a later one answered
  // by the same answer.
  EXPECT_GE(trips.rtt_ms()[2], trips.rtt_ms()[3]);
  EXPECT_EQ(trips.count(), 5u);
}

// Every message goes out in order, marked sent before it is written;
// answered at once, sending ends with done().
TEST(RoundTripsTest, SendPacedWritesEveryMessage) {
  RoundTrips trips(20);
  const SendSchedule now{.start = SendSchedule::Clock::now(), .rate_hz = 1e5};
  std::vector<uint64_t> written;
  bool done = false;
  SendPaced(
      trips, now,
      [&](uint64_t sequence) {
        EXPECT_EQ(trips.sent(), sequence);
        written.push_back(sequence);
        trips.MarkAnswered(sequence);
        return true;
      },
      [&] { done = true; });
  ASSERT_EQ(written.size(), 20u);
  for (uint64_t i = 0; i < 20; ++i) EXPECT_EQ(written[i], i + 1);
  EXPECT_TRUE(done);
  EXPECT_EQ(trips.answered(), 20u);
}

// A write that fails (the stream ended) stops the sending there, without
// closing a stream that is gone.
TEST(RoundTripsTest, SendPacedStopsAtAFailedWrite) {
  RoundTrips trips(10);
  const SendSchedule now{.start = SendSchedule::Clock::now(), .rate_hz = 1e5};
  bool done = false;
  SendPaced(
      trips, now, [](uint64_t sequence) { return sequence < 3; }, [&] { done = true; });
  EXPECT_EQ(trips.sent(), 3u);
  EXPECT_FALSE(done);
}

}  // namespace
}  // namespace hs::cli
