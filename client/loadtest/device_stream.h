#pragma once
// One simulated device of `hapticctl loadtest`: an Interact stream driving
// one tool along a path on a send schedule, timing each pose's round trip
// (sent -> the first frame whose last applied pose sequence is >= it).

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "client/device_path.h"
#include "client/loadtest/frame_counts.h"
#include "client/loadtest/load_report.h"
#include "client/loadtest/round_trips.h"
#include "client/loadtest/send_schedule.h"
#include "common/sim/effects.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {

/// What a device asks for when it opens its stream.
struct DeviceOpen {
  std::string scene{};
  std::string tool{};
  EffectSet needs = EffectSet::Default();
  /// Frames a second (frame_rate_args.h); 0: the server's own rate.
  double frame_rate_hz = 0;
  /// Whether the device reads a local model's surface alone (no planes).
  bool surface_only = true;
};

/// The message that opens a device's stream.
haptics::v1::InteractRequest OpenRequest(const DeviceOpen& open);

class DeviceStream {
 public:
  /// Opens the stream (its open message written). `frame_bytes` gets the
  /// size of a frame now and then, for the echo's replies.
  DeviceStream(haptics::v1::SessionService::Stub& stub, const DeviceOpen& open,
               std::vector<TimedPose> path, std::atomic<int64_t>& frame_bytes);
  /// A stream left open by an early return is cancelled, not waited for.
  ~DeviceStream();

  /// Waits for the first frame: the device is attached. False when the
  /// stream ended (Finish says why).
  bool Attached();

  /// Pose message `sequence` (1-based) of the path, stamped now.
  haptics::v1::InteractRequest Request(uint64_t sequence) const;
  /// The mean size of the path's pose messages (16 spread over it).
  int64_t MeanRequestBytes() const;

  /// Sends the path on `schedule` and reads frames until the stream ends;
  /// frames before the schedule's start are not counted. With
  /// `keep_step_times`, keeps the step time of every frame that applied a
  /// new pose.
  void Run(const SendSchedule& schedule, bool keep_step_times);

  /// What the stream saw since the schedule's start.
  StreamReport Report(double window_s);

  /// The status of a stream that ended before Run.
  grpc::Status Finish();
  /// The status Run ended with.
  const grpc::Status& status() const { return status_; }
  RoundTrips& trips() { return trips_; }
  /// Step times, ms (with keep_step_times).
  std::vector<double>& step_ms() { return step_ms_; }

 private:
  void Read(const SendSchedule& schedule, bool keep_step_times);

  std::vector<TimedPose> path_;
  RoundTrips trips_;
  std::atomic<int64_t>& frame_bytes_out_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<haptics::v1::InteractRequest, haptics::v1::Frame>>
      stream_;
  FrameCounts counts_;
  std::vector<double> step_ms_;
  grpc::Status status_;
};

}  // namespace hs::cli
