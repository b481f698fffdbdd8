#include "haptics/watcher.h"

#include <chrono>

#include "absl/strings/str_cat.h"
#include "client/sdk/frame_view.h"
#include "client/sdk/grpc_error.h"
#include "client/sdk/watcher_impl.h"

namespace haptics {

namespace pb = haptics::v1;

Watcher::Impl::Impl(std::shared_ptr<grpc::Channel> channel, std::string scene, WatchOptions options,
                    Internal internal)
    : channel_(std::move(channel)),
      scene_(std::move(scene)),
      options_(std::move(options)),
      internal_(std::move(internal)) {}

Watcher::Impl::~Impl() {
  Close();
  if (thread_.joinable()) thread_.join();
}

Error Watcher::Impl::Start() {
  thread_ = std::thread(&Impl::Read, this);
  std::unique_lock lock(mutex_);
  const bool answered =
      changed_.wait_for(lock, std::chrono::duration<double>(options_.open_timeout_s),
                        [&] { return frames_ > 0 || ended_; });
  if (frames_ > 0) return {};
  if (answered) return status_;
  lock.unlock();
  Close();
  return {Code::kDeadlineExceeded, absl::StrCat("no frame from scene '", scene_, "' within ",
                                                options_.open_timeout_s, " s")};
}

void Watcher::Impl::Read() {
  pb::WatchRequest request;
  request.set_scene(scene_);
  request.set_frame_rate_hz(options_.frame_rate_hz);
  if (options_.poses) request.add_parts(pb::WATCH_PART_POSES);
  if (options_.contacts) request.add_parts(pb::WATCH_PART_CONTACTS);
  if (options_.forces) request.add_parts(pb::WATCH_PART_FORCES);
  if (options_.local_model) request.add_parts(pb::WATCH_PART_LOCAL_MODEL);
  auto stub = pb::SessionService::NewStub(channel_);
  auto reader = stub->Watch(&context_, request);
  pb::Frame message;
  while (reader->Read(&message)) {
    if (internal_.on_message) internal_.on_message(message);
    Frame frame = hs::sdk::FrameFromProto(message);
    if (options_.on_frame) options_.on_frame(frame);
    std::lock_guard lock(mutex_);
    latest_ = std::move(frame);
    ++frames_;
    changed_.notify_all();
  }
  const grpc::Status status = reader->Finish();
  Error ended;
  {
    std::lock_guard lock(mutex_);
    ended_ = true;
    // A stream this side closed ends CANCELLED: that is no error.
    if (!closed_) status_ = hs::sdk::FromGrpc(status);
    ended = status_;
    changed_.notify_all();
  }
  if (internal_.on_end) internal_.on_end(ended);
}

bool Watcher::Impl::Latest(Frame* out) const {
  std::lock_guard lock(mutex_);
  if (frames_ == 0) return false;
  *out = latest_;
  return true;
}

int64_t Watcher::Impl::frames() const {
  std::lock_guard lock(mutex_);
  return frames_;
}

bool Watcher::Impl::ended() const {
  std::lock_guard lock(mutex_);
  return ended_;
}

Error Watcher::Impl::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

void Watcher::Impl::Close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  context_.TryCancel();
}

Watcher::Watcher(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Watcher::~Watcher() = default;
bool Watcher::Latest(Frame* out) const { return impl_->Latest(out); }
int64_t Watcher::frames() const { return impl_->frames(); }
bool Watcher::ended() const { return impl_->ended(); }
Error Watcher::status() const { return impl_->status(); }
void Watcher::Close() { impl_->Close(); }

}  // namespace haptics

namespace hs::sdk {

haptics::Result<std::unique_ptr<haptics::Watcher>> OpenWatcher(
    std::shared_ptr<grpc::Channel> channel, const std::string& scene, haptics::WatchOptions options,
    haptics::Watcher::Impl::Internal internal) {
  auto impl = std::make_unique<haptics::Watcher::Impl>(std::move(channel), scene,
                                                       std::move(options), std::move(internal));
  if (haptics::Error error = impl->Start(); !error.ok()) return error;
  return std::make_unique<haptics::Watcher>(std::move(impl));
}

}  // namespace hs::sdk
