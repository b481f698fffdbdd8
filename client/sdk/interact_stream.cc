#include "client/sdk/interact_stream.h"

namespace hs::sdk {

namespace pb = haptics::v1;

InteractStream::InteractStream(const std::shared_ptr<grpc::Channel>& channel,
                               const pb::InteractRequest::Open& open, Callbacks callbacks,
                               std::chrono::system_clock::time_point deadline)
    : callbacks_(std::move(callbacks)) {
  if (deadline != std::chrono::system_clock::time_point::max()) context_.set_deadline(deadline);
  stream_ = pb::SessionService::NewStub(channel)->Interact(&context_);
  pb::InteractRequest request;
  *request.mutable_open() = open;
  // A failed write leaves a dead call whose first Read returns false: the
  // reader reports the end either way.
  stream_->Write(request);
  reader_ = std::thread([this] {
    pb::Frame frame;
    while (stream_->Read(&frame)) {
      if (callbacks_.on_frame) callbacks_.on_frame(frame);
    }
    if (callbacks_.on_end) callbacks_.on_end();
  });
}

InteractStream::~InteractStream() {
  if (!finished_) {
    Cancel();
    Finish();
  }
}

bool InteractStream::Write(const pb::InteractRequest& request) { return stream_->Write(request); }

void InteractStream::WritesDone() { stream_->WritesDone(); }

void InteractStream::Cancel() { context_.TryCancel(); }

grpc::Status InteractStream::Finish() {
  reader_.join();
  finished_ = true;
  return stream_->Finish();
}

}  // namespace hs::sdk
