#pragma once
// Builds a tool's local contact model (local_model.h) from the faces of the
// fixed objects near its proxy.

#include <span>

#include "common/contact/contact_query.h"
#include "common/sim/local_model.h"
#include "common/sim/proxy.h"
#include "common/sim/step_frame.h"

namespace hs {

struct LocalModelOptions {
  /// The model's validity radius, metres, > 0.
  double radius_m = 0.01;
  /// The most planes a model holds (the nearest are kept).
  int max_planes = 16;
  double force_clamp_n = 10;
  bool friction = false;
};

/// Fills `model` for `tool` (its pose field ignored) at `proxy`, moved
/// toward the device at `p_WD`, among
/// `obstacles` (fixed objects, ids `ids`; `proxy.obstacle` is an id). A
/// plane is taken for each face whose box comes within the radius of the
/// tool's box and whose plane the tool is in front of by at most the
/// radius; planes that coincide are taken once. Allocates nothing once
/// `model.planes` and the query buffers are large enough.
void BuildLocalModel(const PosedObject& tool, const ProxyState& proxy, const Vector3d& p_WD,
                     std::span<const PosedObject> obstacles, std::span<const ObjectId> ids,
                     const LocalModelOptions& options, LocalModel& model);

/// Fills `model` from `built` (a model BuildLocalModel made) for the proxy
/// at `proxy`, moved toward `p_WD`, without a new face search: each
/// plane's gap and tool point follow the proxy's shift since `built` was
/// taken, a plane the proxy has gone more than `behind_m` behind (a face
/// it has slid past) is left out, and the validity radius shrinks by
/// `moved_m`, how far any point of the tool has moved since (the model
/// holds within what is left of the built one's sphere; at least
/// `behind_m`). Revision, clamp and friction are `built`'s. Allocates
/// nothing once `model.planes` is as large as `built`'s.
void ReanchorLocalModel(const LocalModel& built, const ProxyState& proxy, const Vector3d& p_WD,
                        double moved_m, double behind_m, LocalModel& model);

}  // namespace hs
