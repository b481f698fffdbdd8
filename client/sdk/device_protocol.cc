#include "client/sdk/device_protocol.h"

#include <cmath>

#include "common/api/local_model_convert.h"

namespace hs::sdk {

namespace pb = haptics::v1;

DeviceProtocol::DeviceProtocol(const DeviceConfig& config) : config_(config) {}

pb::InteractRequest::Open DeviceProtocol::Open() const {
  const haptics::DeviceOptions& options = config_.options;
  pb::InteractRequest::Open open;
  open.set_scene(config_.scene);
  open.set_tool(config_.tool);
  open.set_take_over(options.take_over);
  open.set_frame_rate_hz(options.frame_rate_hz > 0 ? options.frame_rate_hz : options.rate_hz);
  open.add_needs(pb::EFFECT_FORCE);
  open.add_needs(pb::EFFECT_FRICTION);
  if (options.local_model) {
    open.add_needs(pb::EFFECT_LOCAL_MODEL);
    // The loop renders from a model's surface where it has one
    // (client/haptic_loop) and needs no planes beside it.
    open.set_surface_only(true);
  }
  for (pb::Effect effect : config_.extra_needs) open.add_needs(effect);
  return open;
}

void DeviceProtocol::Begin(uint64_t stream) {
  sequence_ = 0;
  first_pose_time_ns_ = 0;
  has_model_ = false;
  first_frame_ = false;
  last_revision_ = 0;
  feed_.stream = stream;
  feed_.connected = false;
}

void DeviceProtocol::End() { feed_.connected = false; }

void DeviceProtocol::PoseRequest(const PoseSample& sample, pb::InteractRequest& request) {
  request.Clear();
  pb::ToolPose* pose = request.mutable_pose();
  if (sequence_ == 0) first_pose_time_ns_ = sample.time_ns;
  pose->set_sequence(++sequence_);
  pose->set_device_time_ns(sample.time_ns);
  pose->mutable_pose()->mutable_position_m()->set_x(sample.position_m[0]);
  pose->mutable_pose()->mutable_position_m()->set_y(sample.position_m[1]);
  pose->mutable_pose()->mutable_position_m()->set_z(sample.position_m[2]);
  pb::Quaternion* q = pose->mutable_pose()->mutable_orientation();
  q->set_w(sample.orientation_wxyz[0]);
  q->set_x(sample.orientation_wxyz[1]);
  q->set_y(sample.orientation_wxyz[2]);
  q->set_z(sample.orientation_wxyz[3]);
  if (!config_.options.local_model) return;
  const double now_s = static_cast<double>(sample.time_ns) * 1e-9;
  const int64_t round_trip_ns = round_trip_peak_ns_.exchange(-1);
  if (round_trip_ns >= 0) {
    model_requester_.AddRoundTrip(now_s, static_cast<double>(round_trip_ns) * 1e-9);
  }
  const ModelRequest model = model_requester_.ForPose(
      now_s, Vector3d(sample.position_m[0], sample.position_m[1], sample.position_m[2]),
      sample.beyond_validity_ticks);
  pose->set_model_stale(model.model_stale || !has_model_);
  pose->set_validity_radius_m(model.validity_radius_m);
}

FrameRead DeviceProtocol::Read(const pb::Frame& frame, int64_t now_ns) {
  const FrameRead read = Take(frame, now_ns);
  if (config_.on_frame) config_.on_frame(frame, read);
  return read;
}

FrameRead DeviceProtocol::Take(const pb::Frame& frame, int64_t now_ns) {
  FrameRead read;
  if (!first_frame_) {
    first_frame_ = true;
    feed_.connected = true;
    read.first_frame = true;
    read.feed_changed = true;
  }
  // Until the server applies this stream's first pose, its frames name the
  // pose its tool last had: another device's, or an earlier stream's.
  const int64_t first_pose_time_ns = first_pose_time_ns_.load();
  if (frame.last_pose_sequence() > 0 && frame.last_pose_sequence() <= sequence_.load() &&
      first_pose_time_ns > 0 && frame.last_pose_device_time_ns() >= first_pose_time_ns) {
    read.applied_sequence = frame.last_pose_sequence();
    read.round_trip_ns = now_ns - frame.last_pose_device_time_ns();
    int64_t peak = round_trip_peak_ns_.load();
    while (read.round_trip_ns > peak &&
           !round_trip_peak_ns_.compare_exchange_weak(peak, read.round_trip_ns)) {
    }
  }
  // A frame that applied none of this stream's poses holds the tool's
  // state for another pose (its last device's, or the scene's): its force
  // and model are not this device's to render.
  if (read.applied_sequence == 0) return read;
  for (const pb::ToolState& tool : frame.tools()) {
    if (tool.tool() != config_.tool) continue;
    if (!config_.options.local_model) {
      const pb::Vector3& f = tool.force_w_n();
      const double force[3] = {f.x(), f.y(), f.z()};
      const bool finite =
          std::isfinite(force[0]) && std::isfinite(force[1]) && std::isfinite(force[2]);
      for (int i = 0; i < 3; ++i) feed_.force_n[i] = finite ? force[i] : 0;
      read.feed_changed = true;
      continue;
    }
    if (!tool.has_local_model()) continue;
    const uint64_t revision = tool.local_model().revision();
    if (revision != 0 && revision == last_revision_) continue;
    absl::StatusOr<LocalModel> model = LocalModelFromProto(tool.local_model());
    if (!model.ok()) {
      read.model_rejected = true;  // the loop keeps the last model
      continue;
    }
    last_revision_ = revision;
    if (model->surface && model->surface->has_body()) {
      surfaces_[surfaces_next_++ % surfaces_.size()] = model->surface;
    } else if (model->surface) {
      // Newest first: after a scene is rebuilt, revisions start again.
      for (size_t k = 1; k <= surfaces_.size(); ++k) {
        const std::shared_ptr<const ModelSurface>& held =
            surfaces_[(surfaces_next_ - k) % surfaces_.size()];
        if (held && held->revision == model->surface->revision &&
            held->center_W == model->surface->center_W &&
            held->radius_m == model->surface->radius_m) {
          model->surface = held;
          break;
        }
      }
    }
    feed_.model = *std::move(model);
    feed_.model_stream = feed_.stream;
    ++feed_.model_serial;
    has_model_ = true;
    read.new_model = true;
    read.feed_changed = true;
  }
  return read;
}

}  // namespace hs::sdk
