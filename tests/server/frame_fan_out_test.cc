#include "server/frame_fan_out.h"

#include <gtest/gtest.h>

#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <vector>

namespace hs {
namespace {

// A stream that records the steps offered to it; while `hold` is set, an
// offer waits until it is cleared (a write stuck on gRPC).
class SlowSink : public FrameSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    std::unique_lock lock(mu_);
    steps_.push_back(snapshot->step);
    cv_.notify_all();
    cv_.wait(lock, [this] { return !hold_; });
  }
  void Close(const absl::Status& status) override {
    std::lock_guard lock(mu_);
    closed_ = status;
    in_sink_call_ = FrameFanOut::InSinkCall();
  }
  void Hold(bool hold) {
    {
      std::lock_guard lock(mu_);
      hold_ = hold;
    }
    cv_.notify_all();
  }
  // Waits until `n` steps were offered.
  void WaitForSteps(size_t n) {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return steps_.size() >= n; });
  }
  std::vector<int64_t> steps() {
    std::lock_guard lock(mu_);
    return steps_;
  }
  std::optional<absl::Status> closed() {
    std::lock_guard lock(mu_);
    return closed_;
  }
  // Whether Close ran inside the fan-out's round (FrameFanOut::InSinkCall).
  bool closed_in_sink_call() {
    std::lock_guard lock(mu_);
    return in_sink_call_;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool hold_ = false;
  std::vector<int64_t> steps_;
  std::optional<absl::Status> closed_;
  bool in_sink_call_ = false;
};

// Step `step` of a 1 kHz scene.
std::shared_ptr<const StepSnapshot> Step(int64_t step) {
  auto snapshot = std::make_shared<StepSnapshot>();
  snapshot->step = step;
  snapshot->time_s = 0.001 * static_cast<double>(step);
  return snapshot;
}

// A stream at 250 frames a second: after a frame, the next is due at the
// next multiple of 4 ms.
class PacedSink : public SlowSink {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    last_time_s_ = snapshot->time_s;
    SlowSink::Offer(std::move(snapshot));
  }
  double NextDueS() const override { return (std::floor(last_time_s_ / 0.004 + 1e-6) + 1) * 0.004; }

 private:
  double last_time_s_ = 0;  // the frames thread's only
};

// Every frame pushed reaches every stream, in step order, and Stop hands
// over everything queued before it returns.
TEST(FrameFanOutTest, EveryFrameInOrderAndStopDrains) {
  Metrics metrics;
  StreamRegistry streams(SceneTools{});
  SlowSink a, b;
  ASSERT_TRUE(streams.AttachViewer(&a, EffectSet::All()).ok());
  ASSERT_TRUE(streams.AttachViewer(&b, EffectSet::All()).ok());
  FrameFanOut fan_out(streams, metrics, 0);
  std::vector<int64_t> expected;
  for (int64_t step = 1; step <= 50; ++step) {
    fan_out.Push(Step(step));
    expected.push_back(step);
  }
  fan_out.Stop();
  EXPECT_EQ(a.steps(), expected);
  EXPECT_EQ(b.steps(), expected);
}

// While a stream's write is stuck, frames queue up to kMaxQueuedFrames;
// past that the oldest go, counted in hs_frames_dropped_total, and the
// rest still arrive in order.
TEST(FrameFanOutTest, StalledHandOverDropsTheOldest) {
  Metrics metrics;
  StreamRegistry streams(SceneTools{});
  SlowSink sink;
  ASSERT_TRUE(streams.AttachViewer(&sink, EffectSet::All()).ok());
  FrameFanOut fan_out(streams, metrics, 0);
  sink.Hold(true);
  fan_out.Push(Step(1));
  sink.WaitForSteps(1);  // step 1 is being offered, stuck
  const int64_t queued = FrameFanOut::kMaxQueuedFrames + 6;
  for (int64_t step = 2; step <= 1 + queued; ++step) fan_out.Push(Step(step));
  sink.Hold(false);
  fan_out.Stop();
  const std::vector<int64_t> steps = sink.steps();
  ASSERT_EQ(steps.size(), 1 + FrameFanOut::kMaxQueuedFrames);
  EXPECT_EQ(steps[0], 1);
  EXPECT_EQ(steps[1], 2 + 6);  // steps 2-7 were dropped
  EXPECT_EQ(steps.back(), 1 + queued);
  EXPECT_NE(metrics.Text().find("hs_frames_dropped_total 6"), std::string::npos) << metrics.Text();
}

// The frames thread is offered only the steps its streams take: with two
// streams at 250 frames a second, steps 4, 8, ...; a stream that comes
// between two of them gets the very next step, and with a viewer that
// takes every step, every step is offered again.
TEST(FrameFanOutTest, OnlyStepsAStreamTakesAreOffered) {
  Metrics metrics;
  StreamRegistry streams(SceneTools{});
  PacedSink a, b;
  SlowSink viewer;
  ASSERT_TRUE(streams.AttachViewer(&a, EffectSet::All()).ok());
  ASSERT_TRUE(streams.AttachViewer(&b, EffectSet::All()).ok());
  FrameFanOut fan_out(streams, metrics, 0);
  // Pushes `step` and, when the streams take it, waits until its round has
  // ended: the next push sees when the streams take their next frame.
  const auto push = [&](int64_t step, SlowSink& taker) {
    const size_t taken = taker.steps().size();
    fan_out.Push(Step(step));
    if (step % 4 != 0 && step != 1) return;
    taker.WaitForSteps(taken + 1);
    fan_out.WaitForSinkCalls();
  };
  for (int64_t step = 1; step <= 9; ++step) push(step, a);
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  fan_out.Push(Step(10));
  for (int64_t step = 11; step <= 13; ++step) fan_out.Push(Step(step));
  fan_out.Stop();
  EXPECT_EQ(a.steps(), (std::vector<int64_t>{1, 4, 8, 10, 11, 12, 13}));
  EXPECT_EQ(b.steps(), a.steps());
  EXPECT_EQ(viewer.steps(), (std::vector<int64_t>{10, 11, 12, 13}));
}

// WaitForSinkCalls returns only once an offer under way has ended: after a
// stream leaves the registry and WaitForSinkCalls returns, nothing more is
// offered to it.
TEST(FrameFanOutTest, WaitForSinkCallsOutlastsTheOfferUnderWay) {
  Metrics metrics;
  StreamRegistry streams(SceneTools{});
  SlowSink sink;
  ASSERT_TRUE(streams.AttachViewer(&sink, EffectSet::All()).ok());
  FrameFanOut fan_out(streams, metrics, 0);
  sink.Hold(true);
  fan_out.Push(Step(1));
  sink.WaitForSteps(1);
  streams.Detach(&sink);
  std::thread release([&] { sink.Hold(false); });
  fan_out.WaitForSinkCalls();  // returns after the stuck offer of step 1
  release.join();
  fan_out.Push(Step(2));
  fan_out.Stop();
  EXPECT_EQ(sink.steps(), std::vector<int64_t>{1});
}

// The ends the registry queues reach their streams on the frames thread,
// after the frames of the same round and inside the round
// (FrameFanOut::InSinkCall); an ended stream gets no frame after; ends
// queued after Stop are handed over by HandOverEnds.
TEST(FrameFanOutTest, EndsAreHandedOverAfterTheRoundsFrames) {
  Metrics metrics;
  StreamRegistry streams(SceneTools{.tools = {{"probe", 0}}, .object_count = 1});
  SlowSink trainee, instructor, viewer;
  ASSERT_TRUE(streams.AttachDevice(&trainee, {"probe", EffectSet::All()}).ok());
  ASSERT_TRUE(streams.AttachViewer(&viewer, EffectSet::All()).ok());
  FrameFanOut fan_out(streams, metrics, 0);
  fan_out.Push(Step(1));
  trainee.WaitForSteps(1);
  const absl::Status taken = absl::AbortedError("taken over");
  ASSERT_TRUE(streams.AttachDevice(&instructor, {"probe", EffectSet::All()}, &taken).ok());
  EXPECT_FALSE(trainee.closed().has_value());  // the registry calls no stream
  fan_out.Push(Step(2));
  instructor.WaitForSteps(1);
  fan_out.Stop();
  ASSERT_TRUE(trainee.closed().has_value());
  EXPECT_EQ(*trainee.closed(), taken);
  EXPECT_TRUE(trainee.closed_in_sink_call());
  EXPECT_EQ(trainee.steps(), std::vector<int64_t>{1});
  EXPECT_FALSE(FrameFanOut::InSinkCall());

  streams.CloseAll(absl::UnavailableError("bye"));
  fan_out.HandOverEnds();
  ASSERT_TRUE(viewer.closed().has_value());
  EXPECT_EQ(viewer.closed()->code(), absl::StatusCode::kUnavailable);
  ASSERT_TRUE(instructor.closed().has_value());
  EXPECT_EQ(viewer.steps(), (std::vector<int64_t>{1, 2}));
}

}  // namespace
}  // namespace hs
