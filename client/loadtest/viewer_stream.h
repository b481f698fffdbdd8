#pragma once
// One viewer of `hapticctl loadtest`: a Watch stream of every part of the
// scene, counting its frames, until the scene is deleted or Stop.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

#include "client/loadtest/frame_counts.h"
#include "client/loadtest/load_report.h"
#include "client/loadtest/send_schedule.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {

class ViewerStream {
 public:
  /// Opens the Watch stream of `scene`.
  ViewerStream(haptics::v1::SessionService::Stub& stub, const std::string& scene);

  /// Reads frames until the stream ends, counting those from `start` on.
  void Run(SendSchedule::Clock::time_point start);
  /// Ends the stream (Run returns); from any thread.
  void Stop();
  /// Frames, steps and the counters' growth; frames_per_s over `window_s`.
  StreamReport Report(double window_s) const;

 private:
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReader<haptics::v1::Frame>> reader_;
  FrameCounts counts_;
};

}  // namespace hs::cli
