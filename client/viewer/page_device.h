#pragma once
// A viewer page driving a tool: one Interact stream that the page's poses
// go out on. The stream says whether the page got the tool: its first
// frame means held; its end, released or refused (another device holds
// the tool, no such tool), with the server's message.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "common/core/types.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {

class PageDevice {
 public:
  /// Called from the stream's reader thread: "held", then "released" or
  /// "refused" with a message.
  using Report = std::function<void(const std::string& state, const std::string& message)>;

  /// Opens the stream for `tool` of `scene`, and sends `X_WD_now`, the
  /// tool's device pose as last watched, when given: the server then has
  /// the device's first pose at once, not after the page's own, which a
  /// page slowed by a loaded machine may send after the server's device
  /// timeout has released the tool. KeepAlive resends it until the page
  /// sends another.
  PageDevice(const std::shared_ptr<grpc::Channel>& channel, const std::string& scene,
             const std::string& tool, Report report,
             const std::optional<Isometry3d>& X_WD_now = std::nullopt);
  /// Ends the stream (the tool is released).
  ~PageDevice();
  PageDevice(const PageDevice&) = delete;
  PageDevice& operator=(const PageDevice&) = delete;

  /// Sends the device pose (validated by the caller). One thread only.
  void SendPose(const Isometry3d& X_WD);
  /// Sends the last pose again when none went out for `idle`, so that a
  /// page whose user holds still keeps the tool (the server releases the
  /// tool of a device that falls silent: docs/server.md). Nothing before
  /// the first pose. The thread of SendPose.
  void KeepAlive(std::chrono::steady_clock::duration idle);
  const std::string& tool() const { return tool_; }

 private:
  const std::string tool_;
  std::unique_ptr<haptics::v1::SessionService::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<haptics::v1::InteractRequest, haptics::v1::Frame>>
      stream_;
  uint64_t sequence_ = 0;
  std::optional<Isometry3d> last_pose_;
  std::chrono::steady_clock::time_point last_sent_;
  std::thread reader_;
};

}  // namespace hs::cli
