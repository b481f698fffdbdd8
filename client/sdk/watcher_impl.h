#pragma once
// A Watcher's stream: a thread reading Watch frames, keeping the newest
// and handing each to the caller's callback.

#include <grpcpp/grpcpp.h>

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "haptics/v1/session_service.grpc.pb.h"
#include "haptics/watcher.h"

namespace haptics {

// Hidden: the Watcher class is exported, its state is not.
class [[gnu::visibility("hidden")]] Watcher::Impl {
 public:
  /// What the SDK's own programs (hapticctl watch) take from the stream
  /// besides WatchOptions::on_frame, on the Watcher's thread: each frame
  /// as the message that came, and the stream's end with its status.
  struct Internal {
    std::function<void(const haptics::v1::Frame&)> on_message;
    std::function<void(const Error&)> on_end;
  };

  Impl(std::shared_ptr<grpc::Channel> channel, std::string scene, WatchOptions options,
       Internal internal = {});
  ~Impl();

  /// Starts the stream and waits for its first frame (or its end, or the
  /// open timeout: DEADLINE_EXCEEDED).
  Error Start();
  bool Latest(Frame * out) const;
  int64_t frames() const;
  bool ended() const;
  Error status() const;
  void Close();

 private:
  void Read();

  const std::shared_ptr<grpc::Channel> channel_;
  const std::string scene_;
  const WatchOptions options_;
  const Internal internal_;
  grpc::ClientContext context_;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Frame latest_;
  int64_t frames_ = 0;
  bool ended_ = false;
  bool closed_ = false;
  Error status_;
};

}  // namespace haptics

namespace hs::sdk {

/// A viewer of `scene`, once its first frame came; else why not.
haptics::Result<std::unique_ptr<haptics::Watcher>> OpenWatcher(
    std::shared_ptr<grpc::Channel> channel, const std::string& scene, haptics::WatchOptions options,
    haptics::Watcher::Impl::Internal internal = {});

}  // namespace hs::sdk
