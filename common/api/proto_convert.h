#pragma once
// Conversions between haptics.v1 messages and the simulation's types: the
// proto <-> domain edge. Incoming values are validated here, before they
// reach the simulation core.

#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/sim/effects.h"
#include "common/sim/step_frame.h"
#include "haptics/v1/scene.pb.h"
#include "haptics/v1/session_service.pb.h"

namespace hs {

/// The largest coordinate, length or size accepted, metres: far beyond any
/// scene, small enough that sums and squares stay finite (a box of 1e308
/// is finite but its diagonal is not).
inline constexpr double kMaxCoordinate = 1e6;

/// INVALID_ARGUMENT "where: what": a message field `where` that breaks the
/// rule `what`.
absl::Status InvalidField(const std::string& where, const std::string& what);

/// A vector, unchanged. INVALID_ARGUMENT naming `where` when not finite or
/// a component is beyond +-kMaxCoordinate.
absl::StatusOr<Vector3d> VectorFromProto(const haptics::v1::Vector3& v, const std::string& where);

/// A pose X_WO. The all-zero quaternion means no rotation; any other must
/// have length 1 within 1e-6. INVALID_ARGUMENT naming `where` otherwise or
/// when a number is not finite.
absl::StatusOr<Isometry3d> PoseFromProto(const haptics::v1::Pose& pose, const std::string& where);

void VectorToProto(const Vector3d& v, haptics::v1::Vector3* out);
void PoseToProto(const Isometry3d& X, haptics::v1::Pose* out);

/// The effects a list of haptics.v1.Effect values names; `empty_means`
/// when the list is empty. INVALID_ARGUMENT naming `where` for an
/// unspecified or unknown value.
absl::StatusOr<EffectSet> EffectsFromProto(const google::protobuf::RepeatedField<int>& effects,
                                           EffectSet empty_means, const std::string& where);

/// Appends the haptics.v1.Effect value of each effect in `effects`, in
/// Effect order.
void EffectsToProto(EffectSet effects, google::protobuf::RepeatedField<int>* out);

/// The haptics.v1.Effect value of `effect`.
haptics::v1::Effect EffectToProto(Effect effect);

/// Which parts of a step a stream receives.
struct FrameParts {
  bool poses = true;
  bool contacts = true;
  bool forces = true;
  bool local_model = true;
  /// The free bodies (the stream needs free-body motion).
  bool bodies = true;
  /// Unset: every tool's state; else the state of the tool of this id only
  /// (none when no tool has it).
  std::optional<ObjectId> only_tool;
};

/// Fills `out`'s tools, stages, clashes and bodies from `frame`, keeping
/// the `parts` asked for; `names` gives object names by ObjectId. Bodies
/// go out only at steps whose free-body stage ran. A local model's surface
/// goes out as its revision, centre and radius, without its faces.
void StepFrameToProto(const StepFrame& frame, const std::vector<std::string>& names,
                      const FrameParts& parts, haptics::v1::Frame* out);

}  // namespace hs
