#include "server/frame_pump.h"

#include <gtest/gtest.h>

#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

#include "server/scene_runner.h"
#include "tests/server/test_server.h"

namespace hs {
namespace {

// A gRPC stream stand-in: records the step of each frame written, and
// completes each write at once unless held.
class FakeWriter : public FrameWriter {
 public:
  void StartWrite(const grpc::ByteBuffer* bytes) override {
    haptics::v1::Frame frame;
    std::vector<grpc::Slice> slices;
    EXPECT_TRUE(bytes->Dump(&slices).ok());
    std::string data;
    for (const grpc::Slice& slice : slices) {
      data.append(reinterpret_cast<const char*>(slice.begin()), slice.size());
    }
    EXPECT_TRUE(frame.ParseFromString(data));
    {
      std::lock_guard lock(mu_);
      steps_.push_back(frame.step());
      in_flight_ = true;
      if (hold_) return;
      in_flight_ = false;
    }
    pump->WriteDone(true);
  }
  void Finish(const absl::Status& status) override {
    {
      std::lock_guard lock(mu_);
      finished_ = status;
    }
    cv_.notify_all();
  }
  // Holds writes from now on; Release completes the one in flight.
  void Hold() {
    std::lock_guard lock(mu_);
    hold_ = true;
  }
  void Release() {
    bool complete = false;
    {
      std::lock_guard lock(mu_);
      hold_ = false;
      complete = in_flight_;
      in_flight_ = false;
    }
    if (complete) pump->WriteDone(true);
  }
  std::vector<int64_t> steps() {
    std::lock_guard lock(mu_);
    return steps_;
  }
  absl::Status WaitForFinish() {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [this] { return finished_.has_value(); });
    return *finished_;
  }
  std::optional<absl::Status> finished() {
    std::lock_guard lock(mu_);
    return finished_;
  }

  FramePump* pump = nullptr;

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool hold_ = false;
  bool in_flight_ = false;
  std::vector<int64_t> steps_;
  std::optional<absl::Status> finished_;
};

// A snapshot of step `step` of a 1 kHz scene with no objects.
std::shared_ptr<const StepSnapshot> Step(int64_t step) {
  auto snapshot = std::make_shared<StepSnapshot>();
  snapshot->step = step;
  snapshot->time_s = 0.001 * static_cast<double>(step);
  snapshot->names = std::make_shared<const std::vector<std::string>>();
  return snapshot;
}

// The rate is 1 to the scene's, or 0 for every step; anything else, and
// what is not finite, is INVALID_ARGUMENT naming the field.
TEST(FramePumpTest, FrameRatesOutsideTheirRangeAreRefused) {
  EXPECT_EQ(*CheckFrameRate(0, 1000, "f"), 0);
  EXPECT_EQ(*CheckFrameRate(1, 1000, "f"), 1);
  EXPECT_EQ(*CheckFrameRate(1000, 1000, "f"), 1000);
  EXPECT_EQ(*CheckFrameRate(10000, 1 / 0.0001, "f"), 10000);  // 1 / step_s rounds
  for (double bad : {0.5, -1.0, 1000.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const absl::StatusOr<double> rate = CheckFrameRate(bad, 1000, "open.frame_rate_hz");
    EXPECT_EQ(rate.status().code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(rate.status().message().find("open.frame_rate_hz"), std::string::npos);
  }
}

// At 250 frames a second on a 1 kHz scene the stream gets its first step,
// then every fourth step on the grid of 4 ms (steps 4, 8, ...) that every
// stream of that rate shares; at 300, the first step at or past each
// multiple of 1/300 s; without a rate it gets every step.
TEST(FramePumpTest, AStreamGetsFramesAtItsRate) {
  Metrics metrics;
  for (const auto& [rate, expected] : std::vector<std::pair<double, std::vector<int64_t>>>{
           {250, {1, 4, 8, 12, 16, 20}},
           {300, {1, 4, 7, 10, 14, 17, 20}},
           {0, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20}}}) {
    FakeWriter writer;
    FramePump pump(writer, nullptr, metrics);
    writer.pump = &pump;
    pump.Configure({.frame_rate_hz = rate});
    for (int64_t step = 1; step <= 20; ++step) pump.Offer(Step(step));
    EXPECT_EQ(writer.steps(), expected) << rate;
  }
}

// A stream whose writes back up gets the newest frame due when it can take
// one, never a queue of old ones; after the stall its rate goes on at the
// next multiple of its period, with no burst.
TEST(FramePumpTest, ABackedUpStreamGetsTheNewestFrame) {
  Metrics metrics;
  FakeWriter writer;
  FramePump pump(writer, nullptr, metrics);
  writer.pump = &pump;
  pump.Configure({.frame_rate_hz = 100});
  writer.Hold();
  for (int64_t step = 1; step <= 95; ++step) pump.Offer(Step(step));  // step 1 stuck in flight
  writer.Release();                                                   // then 90, the newest due
  for (int64_t step = 96; step <= 120; ++step) pump.Offer(Step(step));
  EXPECT_EQ(writer.steps(), (std::vector<int64_t>{1, 90, 100, 110, 120}));
  EXPECT_EQ(pump.dropped(), 8u);  // 10, 20, ..., 80: due, then overtaken
}

// A frame over the stream's limit ends that stream RESOURCE_EXHAUSTED,
// writing nothing; it calls nothing but its writer.
TEST(FramePumpTest, AnOversizedFrameEndsTheStream) {
  Metrics metrics;
  FakeWriter writer;
  FramePump pump(writer, nullptr, metrics);
  writer.pump = &pump;
  pump.Configure({.max_frame_bytes = 4});
  pump.Offer(Step(1));
  ASSERT_TRUE(writer.finished().has_value());
  EXPECT_EQ(writer.finished()->code(), absl::StatusCode::kResourceExhausted) << *writer.finished();
  EXPECT_TRUE(writer.steps().empty());
  EXPECT_TRUE(pump.closed());
  pump.Offer(Step(2));  // nothing after the end
  EXPECT_TRUE(writer.steps().empty());
}

// A stream of a running scene: a FramePump behind a FrameSink, its RPC's
// end (OnDone) detaching it on another thread, as the session service's.
class PumpedStream : public FrameSink {
 public:
  PumpedStream(SceneRunner& runner, Metrics& metrics, size_t max_frame_bytes)
      : runner_(runner), pump_(writer_, this, metrics) {
    writer_.pump = &pump_;
    pump_.Configure({.queue_frames = 1, .max_frame_bytes = max_frame_bytes});
  }
  ~PumpedStream() override {
    if (done_.joinable()) done_.join();
  }
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    pump_.Offer(std::move(snapshot));
  }
  void Close(const absl::Status& status) override { pump_.Close(status); }
  // Waits for the stream's end, then detaches as gRPC's OnDone would.
  absl::Status EndAndDetach() {
    const absl::Status status = writer_.WaitForFinish();
    done_ = std::thread([this] { runner_.Detach(this); });
    done_.join();
    return status;
  }
  size_t frames() { return writer_.steps().size(); }

 private:
  SceneRunner& runner_;
  FakeWriter writer_;
  FramePump pump_;
  std::thread done_;
};

// A frame that cannot be sent ends its stream only: the stream finishes
// without calling back into the runner (no deadlock, TSan quiet), detaches
// when its RPC is done, and the scene goes on for the others.
TEST(FramePumpTest, AFailedFrameEndsItsStreamAndTheSceneGoesOn) {
  Metrics metrics;
  const haptics::v1::SceneSpec spec = testing::SmallScene("pump");
  absl::StatusOr<LoadedScene> loaded = BuildScene(spec, "");
  ASSERT_TRUE(loaded.ok());
  SceneRunner runner(spec, *std::move(loaded), metrics);
  PumpedStream failing(runner, metrics, /*max_frame_bytes=*/4);
  PumpedStream healthy(runner, metrics, kMaxFrameBytes);
  ASSERT_TRUE(runner.AttachDevice(&failing, {"probe", EffectSet::All(), "a"}).ok());
  ASSERT_TRUE(runner.AttachViewer(&healthy, EffectSet::All()).ok());
  const absl::Status ended = failing.EndAndDetach();
  EXPECT_EQ(ended.code(), absl::StatusCode::kResourceExhausted) << ended;
  EXPECT_EQ(runner.Info().devices, 0);
  const int64_t step = runner.Info().step;
  while (runner.Info().step < step + 20) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_GT(healthy.frames(), 0u);
  runner.Detach(&healthy);
  runner.Stop(absl::OkStatus());
}

}  // namespace
}  // namespace hs
