#include "client/viewer/scene_link.h"

#include <chrono>

#include "client/server_call.h"
#include "client/viewer/viewer_json.h"
#include "haptics/v1/scene_service.grpc.pb.h"
#include "haptics/v1/session_service.grpc.pb.h"

namespace hs::cli {
namespace {

namespace pb = haptics::v1;
using Clock = std::chrono::steady_clock;

constexpr double kRetrySeconds = 1.0;
constexpr double kUnaryDeadlineSeconds = 5.0;

std::string Describe(const grpc::Status& status) {
  return StatusCodeName(status.error_code()) + ": " + status.error_message();
}

}  // namespace

SceneLink::SceneLink(std::shared_ptr<grpc::Channel> channel, std::string scene)
    : channel_(std::move(channel)), scene_(std::move(scene)) {
  state_.scene = scene_;
  watch_thread_ = std::thread([this] { WatchLoop(); });
  poll_thread_ = std::thread([this] { PollLoop(); });
}

SceneLink::~SceneLink() {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
    if (watch_context_) watch_context_->TryCancel();
  }
  stop_cv_.notify_all();
  watch_thread_.join();
  poll_thread_.join();
}

SceneLink::Latest SceneLink::latest() const {
  std::lock_guard lock(mu_);
  return latest_;
}

SceneLink::State SceneLink::state() const {
  std::lock_guard lock(mu_);
  State s = state_;
  // Connected means frames flow; the poll's view of the scene says why not.
  s.connected = watching_ && state_.connected;
  if (state_.connected && !watching_)
    s.message = watch_error_.empty() ? "connecting" : watch_error_;
  return s;
}

bool SceneLink::Pause(double seconds) {
  std::unique_lock lock(mu_);
  stop_cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return stopping_; });
  return !stopping_;
}

void SceneLink::WatchLoop() {
  auto stub = pb::SessionService::NewStub(channel_);
  do {
    grpc::ClientContext context;
    {
      std::lock_guard lock(mu_);
      if (stopping_) return;
      watch_context_ = &context;
    }
    pb::WatchRequest request;
    request.set_scene(scene_);  // no parts: every part
    auto stream = stub->Watch(&context, request);
    auto frame = std::make_shared<pb::Frame>();
    Clock::time_point second_start = Clock::now();
    int64_t second_first_step = -1;
    while (stream->Read(frame.get())) {
      const Clock::time_point now = Clock::now();
      std::lock_guard lock(mu_);
      watching_ = true;
      if (second_first_step < 0) second_first_step = frame->step();
      if (now - second_start >= std::chrono::seconds(1)) {
        latest_.step_rate_hz = static_cast<double>(frame->step() - second_first_step) /
                               std::chrono::duration<double>(now - second_start).count();
        second_start = now;
        second_first_step = frame->step();
      }
      latest_.frame = std::move(frame);
      ++latest_.count;
      frame = std::make_shared<pb::Frame>();
    }
    const grpc::Status status = stream->Finish();
    std::lock_guard lock(mu_);
    watch_context_ = nullptr;
    watching_ = false;
    latest_.step_rate_hz = 0;
    watch_error_ = status.ok() ? "the scene's stream ended" : Describe(status);
  } while (Pause(kRetrySeconds));
}

void SceneLink::PollLoop() {
  do {
    Poll();
  } while (Pause(kRetrySeconds));
}

void SceneLink::Poll() {
  auto stub = pb::SceneService::NewStub(channel_);
  pb::GetSceneRequest request;
  request.set_scene(scene_);
  pb::SceneInfo info;
  const grpc::Status status =
      stub->GetScene(ContextWithin(kUnaryDeadlineSeconds).get(), request, &info);
  if (!status.ok()) {
    std::lock_guard lock(mu_);
    state_.connected = false;
    state_.message = status.error_code() == grpc::StatusCode::NOT_FOUND
                         ? "no scene '" + scene_ + "' on the server"
                         : "server: " + Describe(status);
    return;
  }
  std::vector<std::string> tools;
  for (const pb::SceneObject& o : info.spec().objects()) {
    if (o.kind() == pb::OBJECT_KIND_TOOL) tools.push_back(o.name());
  }
  std::shared_ptr<const std::string> geometry;
  bool refetch = false;
  {
    std::lock_guard lock(mu_);
    refetch = info.revision() != state_.revision || !state_.geometry_json;
    geometry = state_.geometry_json;
  }
  std::string geometry_error;
  if (refetch) {
    pb::GetGeometryRequest get;
    get.set_scene(scene_);
    pb::SceneGeometry reply;
    const grpc::Status got =
        stub->GetGeometry(ContextWithin(kUnaryDeadlineSeconds).get(), get, &reply);
    if (got.ok()) {
      geometry = std::make_shared<const std::string>(GeometryJson(reply).dump());
    } else {
      geometry_error = "geometry: " + Describe(got);
    }
  }
  std::lock_guard lock(mu_);
  state_.connected = geometry_error.empty();
  state_.message = geometry_error;
  state_.revision = geometry_error.empty() ? info.revision() : state_.revision;
  state_.step_s = info.step_s();
  state_.tools = std::move(tools);
  state_.geometry_json = std::move(geometry);
}

}  // namespace hs::cli
