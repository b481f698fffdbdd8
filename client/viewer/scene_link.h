#pragma once
// The bridge's side toward the server, for one scene: a Watch stream with
// every part, kept open (again every second after it ends, so that a
// server that goes away and comes back is picked up), and a poll of
// GetScene every second for the scene's revision and held tools, fetching
// GetGeometry whenever the revision changes. Pages read the latest of
// each; nothing here waits for them.

#include <grpcpp/grpcpp.h>

#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "haptics/v1/session_service.pb.h"

namespace hs::cli {

class SceneLink {
 public:
  SceneLink(std::shared_ptr<grpc::Channel> channel, std::string scene);
  ~SceneLink();
  SceneLink(const SceneLink&) = delete;
  SceneLink& operator=(const SceneLink&) = delete;

  /// The newest frame (null before the first), counted from 1.
  struct Latest {
    std::shared_ptr<const haptics::v1::Frame> frame;
    uint64_t count = 0;
    /// Steps per second over the last whole second.
    double step_rate_hz = 0;
  };
  Latest latest() const;

  struct State {
    /// Watching, and the scene known to the server.
    bool connected = false;
    /// Why not, for people ("" when connected).
    std::string message = "connecting";
    std::string scene;
    int64_t revision = -1;
    double step_s = 0;
    /// The scene's tools.
    std::vector<std::string> tools;
    /// The page's geometry JSON of `revision` (null before it is fetched).
    std::shared_ptr<const std::string> geometry_json;
  };
  State state() const;

  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }
  const std::string& scene() const { return scene_; }

 private:
  void WatchLoop();
  void PollLoop();
  // One GetScene, and GetGeometry when the revision moved.
  void Poll();
  // Waits `seconds` or until the link stops; false once stopping.
  bool Pause(double seconds);

  const std::shared_ptr<grpc::Channel> channel_;
  const std::string scene_;
  mutable std::mutex mu_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  grpc::ClientContext* watch_context_ = nullptr;  // under mu_, to cancel
  Latest latest_;
  State state_;
  bool watching_ = false;
  std::string watch_error_;
  std::thread watch_thread_;
  std::thread poll_thread_;
};

}  // namespace hs::cli
