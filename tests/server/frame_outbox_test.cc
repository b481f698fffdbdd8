#include "server/frame_outbox.h"

#include <gtest/gtest.h>

namespace hs {
namespace {

std::shared_ptr<const StepSnapshot> Snapshot(int64_t step) {
  auto s = std::make_shared<StepSnapshot>();
  s->step = step;
  return s;
}

// Latest-wins (capacity 1): frames pushed while a write is in flight
// replace each other, the newest is written next, and each replaced frame
// is counted as dropped.
TEST(FrameOutboxTest, LatestWinsCountsReplacedFrames) {
  FrameOutbox outbox(1);
  EXPECT_FALSE(outbox.Push(Snapshot(1)));
  FrameOutbox::Next next = outbox.TakeNext();
  ASSERT_EQ(next.kind, FrameOutbox::Next::kWrite);
  EXPECT_EQ(next.snapshot->step, 1);
  EXPECT_FALSE(outbox.Push(Snapshot(2)));
  EXPECT_TRUE(outbox.Push(Snapshot(3)));
  EXPECT_TRUE(outbox.Push(Snapshot(4)));
  EXPECT_EQ(outbox.TakeNext().kind, FrameOutbox::Next::kNothing);  // one write at a time
  outbox.WriteDone();
  next = outbox.TakeNext();
  ASSERT_EQ(next.kind, FrameOutbox::Next::kWrite);
  EXPECT_EQ(next.snapshot->step, 4);
  EXPECT_EQ(next.dropped, 2u);
}

// A bounded queue keeps the newest `capacity` frames in order, drops the
// oldest, and after Close sends what waits, then finishes exactly once.
TEST(FrameOutboxTest, BoundedQueueThenCloseFinishesOnce) {
  FrameOutbox outbox(3);
  for (int step = 1; step <= 5; ++step) outbox.Push(Snapshot(step));
  outbox.Close(absl::UnavailableError("bye"));
  outbox.Push(Snapshot(6));  // ignored after Close
  for (int step = 3; step <= 5; ++step) {
    const FrameOutbox::Next next = outbox.TakeNext();
    ASSERT_EQ(next.kind, FrameOutbox::Next::kWrite);
    EXPECT_EQ(next.snapshot->step, step);
    EXPECT_EQ(next.dropped, 2u);
    outbox.WriteDone();
  }
  const FrameOutbox::Next last = outbox.TakeNext();
  ASSERT_EQ(last.kind, FrameOutbox::Next::kFinish);
  EXPECT_EQ(last.status.code(), absl::StatusCode::kUnavailable);
  EXPECT_EQ(outbox.TakeNext().kind, FrameOutbox::Next::kNothing);
}

// Abort (the client is gone) drops waiting frames and finishes as soon as
// the write in flight ends.
TEST(FrameOutboxTest, AbortSkipsWaitingFrames) {
  FrameOutbox outbox(4);
  outbox.Push(Snapshot(1));
  outbox.Push(Snapshot(2));
  ASSERT_EQ(outbox.TakeNext().kind, FrameOutbox::Next::kWrite);
  outbox.Abort(absl::CancelledError("gone"));
  EXPECT_EQ(outbox.TakeNext().kind, FrameOutbox::Next::kNothing);
  outbox.WriteDone();
  EXPECT_EQ(outbox.TakeNext().kind, FrameOutbox::Next::kFinish);
}

}  // namespace
}  // namespace hs
