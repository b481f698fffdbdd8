#pragma once
// The surface of a tool's local models (local_model.h, ModelSurface): the
// faces of the fixed objects the tool may meet near its proxy, and the
// tool's convex hull, for a device's loop to sweep the tool against
// (client/haptic_loop/surface_sweep.h) as the server's proxy sweeps it
// against the objects. A tool's models share one surface until its proxy
// moves on (SurfaceKeeper::Serves).

#include <memory>
#include <span>
#include <vector>

#include "common/contact/contact_query.h"
#include "common/sim/local_model.h"

namespace hs {

/// How far around its centre a surface holds, in validity radii: a
/// device's proxy is within a radius of the server's (the device sizes
/// the radius so), and the server's within kSurfaceMoveFraction of a
/// radius of the centre before the surface is gathered anew.
inline constexpr double kSurfaceReachFraction = 1.5;
inline constexpr double kSurfaceMoveFraction = 0.5;

/// Whether `tool`'s mesh is a convex solid: closed (every edge between two
/// faces), not flat, and no vertex in front of any face's plane by more
/// than 1e-9 of its size. A tool that is not gets no surface.
bool IsConvexTool(const HapticObject& tool);

/// A tool's surfaces: gathers one when the last no longer serves, and
/// keeps what that needs (whether the tool is convex, per geometry
/// version; search buffers that stop growing). Each surface is a new
/// object (frames on other threads may hold the last ones), sized as the
/// last one was.
class SurfaceKeeper {
 public:
  /// The tool's surface for its proxy at `p_WP` with validity radius
  /// `radius_m`: the last one while it serves (the same tool geometry,
  /// radius and obstacles, and the proxy within kSurfaceMoveFraction of
  /// the radius of its centre), else a new one (revision + 1) of every face
  /// of `obstacles` the tool may meet with its origin within
  /// kSurfaceReachFraction radii of `p_WP`, in any orientation. Null for a
  /// tool that is not convex or whose hull or neighbourhood is past the
  /// caps (local_model.h). `fresh`: gather anew whatever.
  const std::shared_ptr<const ModelSurface>& Update(const PosedObject& tool, const Vector3d& p_WP,
                                                    double radius_m,
                                                    std::span<const PosedObject> obstacles,
                                                    bool fresh);
  /// Whether the last Update gave another surface than the one before.
  bool changed() const { return changed_; }

 private:
  struct ObstacleKey {
    const void* model;
    uint64_t geometry_version;
    uint64_t material_version;
    Isometry3d X_WO;
  };
  bool Serves(const PosedObject& tool, const Vector3d& p_WP, double radius_m,
              std::span<const PosedObject> obstacles) const;
  // Fills `out` (its revision left) as Update says; false past the caps.
  bool Gather(const PosedObject& tool, const Vector3d& center_W, double radius_m,
              std::span<const PosedObject> obstacles, ModelSurface& out);

  // What the last surface was gathered for.
  const void* tool_model_ = nullptr;
  uint64_t tool_version_ = 0;
  bool convex_ = false;
  double tool_reach_m_ = 0;  // the tool's farthest vertex from its origin
  double radius_m_ = 0;
  Vector3d center_W_ = Vector3d::Zero();
  std::vector<ObstacleKey> obstacles_;
  bool gathered_ = false;
  bool changed_ = false;
  uint64_t revisions_ = 0;
  std::shared_ptr<const ModelSurface> surface_;
  std::vector<FaceId> faces_;
  std::vector<int32_t> vertex_index_;
};

}  // namespace hs
