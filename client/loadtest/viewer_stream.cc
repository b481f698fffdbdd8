#include "client/loadtest/viewer_stream.h"

namespace hs::cli {

namespace pb = haptics::v1;

ViewerStream::ViewerStream(pb::SessionService::Stub& stub, const std::string& scene) {
  pb::WatchRequest request;
  request.set_scene(scene);
  reader_ = stub.Watch(&context_, request);
}

void ViewerStream::Run(SendSchedule::Clock::time_point start) {
  pb::Frame frame;
  while (reader_->Read(&frame)) {
    if (SendSchedule::Clock::now() >= start) counts_.Add(frame);
  }
  reader_->Finish();
}

void ViewerStream::Stop() { context_.TryCancel(); }

StreamReport ViewerStream::Report(double window_s) const {
  StreamReport report;
  counts_.Fill(report, window_s);
  return report;
}

}  // namespace hs::cli
