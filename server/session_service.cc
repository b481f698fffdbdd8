#include "server/session_service.h"

#include <chrono>
#include <cmath>
#include <mutex>

#include "absl/strings/str_cat.h"
#include "common/api/proto_convert.h"
#include "server/frame_pump.h"
#include "server/grpc_status.h"
#include "server/raw_message.h"

namespace hs {
namespace {

namespace pb = haptics::v1;

// The frame-writing half shared by both stream kinds: `Base` is a
// ServerBidiReactor or ServerWriteReactor. Deletes itself when done.
template <class Base>
class FrameStream : public Base, public FrameSink, private FrameWriter {
 public:
  void Offer(std::shared_ptr<const StepSnapshot> snapshot) override {
    pump_.Offer(std::move(snapshot));
  }
  double NextDueS() const override { return pump_.next_due_s(); }
  void Close(const absl::Status& status) override { pump_.Close(status); }
  void OnWriteDone(bool ok) override {
    if (!ok) Detach();  // the client is gone: let go of the tool at once
    pump_.WriteDone(ok);
  }
  void OnCancel() override { End(absl::CancelledError("cancelled by the client"), true); }
  void OnDone() override {
    Detach();
    if (!caller_.empty()) registry_.quotas().Give(caller_, Quota::kStreams);
    if (counted_) {
      registry_.RemoveClient();
      registry_.metrics().AddClients(device_, -1);
    }
    delete this;
  }

 protected:
  FrameStream(SceneRegistry& registry, const AccessPolicy& access,
              const grpc::CallbackServerContext& context, bool device)
      : registry_(registry),
        device_(device),
        pump_(*this, this, registry.metrics()),
        access_(access),
        context_(context) {}

  // Ends the stream from this side (a gRPC thread, never a FrameSink call):
  // lets go of the scene (and the tool) at once, so that the client seeing
  // the end can claim the tool again; then sends the frames waiting (none
  // when `abort`) and finishes.
  void End(const absl::Status& status, bool abort) {
    Detach();
    if (abort) {
      pump_.Abort(status);
    } else {
      pump_.Close(status);
    }
  }

  // The caller, when it may do `access` on `scene`.
  absl::StatusOr<Caller> CheckCaller(Access access, const std::string& scene) const {
    return access_.Check(context_, access, scene);
  }

  // Ends the stream with `status` (after the frames already waiting).
  void Fail(const absl::Status& status, const char* method) {
    registry_.metrics().AddRejected(method, absl::StatusCodeToString(status.code()));
    End(status, /*abort=*/false);
  }

  // Checks the caller may drive or watch `scene`, counts the client and
  // finds its scene; on error the stream is failed.
  bool Open(const std::string& scene, const char* method) {
    absl::StatusOr<Caller> caller = CheckCaller(device_ ? Access::kDrive : Access::kWatch, scene);
    if (!caller.ok()) {
      Fail(caller.status(), method);
      return false;
    }
    if (absl::Status s = registry_.quotas().Take(caller->id, Quota::kStreams); !s.ok()) {
      Fail(s, method);
      return false;
    }
    caller_ = caller->id;
    holder_ = caller->name;
    if (absl::Status s = registry_.AddClient(); !s.ok()) {
      Fail(s, method);
      return false;
    }
    counted_ = true;
    registry_.metrics().AddClients(device_, +1);
    absl::StatusOr<std::shared_ptr<SceneRunner>> runner = registry_.Find(scene);
    if (!runner.ok()) {
      Fail(runner.status(), method);
      return false;
    }
    std::lock_guard lock(runner_mu_);
    runner_ = *runner;
    return true;
  }

  // Sets what the stream asked for, checking its frame rate against the
  // scene's; on error the stream is failed.
  bool Configure(FramePump::Options options, const char* method) {
    absl::StatusOr<double> rate =
        CheckFrameRate(options.frame_rate_hz, 1 / runner_->step_s(), "frame_rate_hz");
    if (!rate.ok()) {
      Fail(rate.status(), method);
      return false;
    }
    options.queue_frames = device_ ? 1 : kViewerQueueFrames;
    options.device = device_;
    pump_.Configure(options);
    return true;
  }

  // Runs `start_operation` unless the stream is closed, atomically with
  // Finish: no operation starts after Finish.
  template <class F>
  void UnlessClosed(F start_operation) {
    pump_.UnlessClosed(start_operation);
  }

  SceneRegistry& registry_;
  const bool device_;
  // Set once by Open, on the reading thread; End may read it from others.
  std::mutex runner_mu_;
  std::shared_ptr<SceneRunner> runner_;
  std::string holder_;  // the caller's name (Caller::name), set by Open

 private:
  // Leaves the scene, if attached: from a gRPC thread only.
  void Detach() {
    std::shared_ptr<SceneRunner> runner;
    {
      std::lock_guard lock(runner_mu_);
      runner = runner_;
    }
    if (runner) runner->Detach(this);
  }

  void StartWrite(const grpc::ByteBuffer* bytes) override { Base::StartWrite(bytes); }
  void Finish(const absl::Status& status) override { Base::Finish(ToGrpcStatus(status)); }

  FramePump pump_;
  const AccessPolicy& access_;
  const grpc::CallbackServerContext& context_;
  bool counted_ = false;
  std::string caller_;  // set once its stream quota is taken
};

// Reads bytes and parses them here (raw_message.h): a message that is no
// InteractRequest ends the stream with INVALID_ARGUMENT.
class InteractReactor
    : public FrameStream<grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>> {
 public:
  InteractReactor(SceneRegistry& registry, const AccessPolicy& access,
                  const grpc::CallbackServerContext& context)
      : FrameStream(registry, access, context, true) {
    UnlessClosed([this] { StartRead(&read_); });
  }

  void OnReadDone(bool ok) override {
    if (!ok) {
      // The device stopped sending: the stream ends once it has its frame.
      End(absl::OkStatus(), /*abort=*/false);
      return;
    }
    if (absl::Status s = ParseMessage(read_, request_); !s.ok()) {
      Fail(s, "Interact");
      return;
    }
    if (!(opened_ ? ApplyPose() : OpenSession())) return;
    UnlessClosed([this] { StartRead(&read_); });
  }

 private:
  bool OpenSession() {
    if (!request_.has_open()) {
      Fail(absl::InvalidArgumentError("the first message must be 'open'"), "Interact");
      return false;
    }
    const pb::InteractRequest::Open& open = request_.open();
    if (!Open(open.scene(), "Interact")) return false;
    absl::StatusOr<EffectSet> needs =
        EffectsFromProto(open.needs(), EffectSet::Default(), "open.needs");
    if (!needs.ok()) {
      Fail(needs.status(), "Interact");
      return false;
    }
    // Taking a tool from its device is an instructor's: the admin role.
    absl::Status taken;
    if (open.take_over()) {
      absl::StatusOr<Caller> admin = this->CheckCaller(Access::kAdmin, open.scene());
      if (!admin.ok()) {
        Fail(absl::PermissionDeniedError("take_over needs the admin role on the scene: " +
                                         std::string(admin.status().message())),
             "Interact");
        return false;
      }
      taken = absl::AbortedError("tool '" + open.tool() + "' was taken over by " + admin->name);
    }
    FrameParts parts;
    parts.bodies = needs->Has(Effect::kFreeBodyMotion);
    if (!Configure({.parts = parts, .frame_rate_hz = open.frame_rate_hz()}, "Interact")) {
      return false;
    }
    if (absl::Status s = runner_->AttachDevice(this, {open.tool(), *needs, holder_},
                                               open.take_over() ? &taken : nullptr);
        !s.ok()) {
      Fail(s, "Interact");
      return false;
    }
    opened_ = true;
    surface_only_ = open.surface_only();
    return true;
  }

  bool ApplyPose() {
    if (!request_.has_pose()) {
      Fail(absl::InvalidArgumentError("'open' may only come first"), "Interact");
      return false;
    }
    const pb::ToolPose& pose = request_.pose();
    absl::StatusOr<Isometry3d> X_WD = PoseFromProto(pose.pose(), "pose.pose");
    if (!X_WD.ok()) {
      Fail(X_WD.status(), "Interact");
      return false;
    }
    if (!(std::isfinite(pose.validity_radius_m()) && pose.validity_radius_m() >= 0)) {
      Fail(absl::InvalidArgumentError("pose.validity_radius_m must be finite and >= 0"),
           "Interact");
      return false;
    }
    runner_->SetDevicePose(this, *X_WD, AppliedPose{pose.sequence(), pose.device_time_ns()},
                           {.stale = pose.model_stale(),
                            .validity_radius_m = pose.validity_radius_m(),
                            .surface_only = surface_only_});
    return true;
  }

  grpc::ByteBuffer read_;
  pb::InteractRequest request_;
  bool opened_ = false;
  // The device reads its local model's surface alone (Open.surface_only).
  bool surface_only_ = false;
};

// What a viewer's parts need the scene to compute.
absl::StatusOr<std::pair<FrameParts, EffectSet>> ViewerNeeds(const pb::WatchRequest& request) {
  if (request.parts().empty()) return std::pair{FrameParts{}, EffectSet::Default()};
  FrameParts parts{false, false, false, false, false, std::nullopt};
  EffectSet needs;
  for (int i = 0; i < request.parts_size(); ++i) {
    switch (request.parts(i)) {
      case pb::WATCH_PART_POSES:
        parts.poses = true;
        break;
      case pb::WATCH_PART_CONTACTS:
        parts.contacts = true;
        needs = needs | EffectSet{Effect::kContactSet, Effect::kReversingVector};
        break;
      case pb::WATCH_PART_FORCES:
        parts.forces = true;
        needs = needs | EffectSet{Effect::kForce, Effect::kFriction};
        break;
      case pb::WATCH_PART_LOCAL_MODEL:
        parts.local_model = true;
        needs = needs | EffectSet{Effect::kLocalModel, Effect::kFriction};
        break;
      case pb::WATCH_PART_BODIES:
        parts.bodies = true;
        needs = needs.With(Effect::kFreeBodyMotion);
        break;
      default:
        return absl::InvalidArgumentError(absl::StrCat("parts[", i, "]: unknown part"));
    }
  }
  return std::pair{parts, needs};
}

class WatchReactor : public FrameStream<grpc::ServerWriteReactor<grpc::ByteBuffer>> {
 public:
  WatchReactor(SceneRegistry& registry, const AccessPolicy& access,
               const grpc::CallbackServerContext& context, const grpc::ByteBuffer& bytes)
      : FrameStream(registry, access, context, false) {
    pb::WatchRequest request;
    if (absl::Status s = ParseMessage(bytes, request); !s.ok()) {
      Fail(s, "Watch");
      return;
    }
    if (!Open(request.scene(), "Watch")) return;
    absl::StatusOr<std::pair<FrameParts, EffectSet>> needs = ViewerNeeds(request);
    if (!needs.ok()) {
      Fail(needs.status(), "Watch");
      return;
    }
    if (!Configure({.parts = needs->first, .frame_rate_hz = request.frame_rate_hz()}, "Watch")) {
      return;
    }
    if (absl::Status s = runner_->AttachViewer(this, needs->second); !s.ok()) Fail(s, "Watch");
  }
};

}  // namespace

grpc::ServerBidiReactor<grpc::ByteBuffer, grpc::ByteBuffer>* SessionServiceImpl::Interact(
    grpc::CallbackServerContext* context) {
  return new InteractReactor(registry_, access_, *context);
}

grpc::ServerWriteReactor<grpc::ByteBuffer>* SessionServiceImpl::Watch(
    grpc::CallbackServerContext* context, const grpc::ByteBuffer* request) {
  return new WatchReactor(registry_, access_, *context, *request);
}

}  // namespace hs
