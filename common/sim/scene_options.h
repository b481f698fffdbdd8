#pragma once
// How a scene steps: its step length, the effects it allows, its contact
// method and tolerances, the force clamp, gravity and damping of free
// bodies, and whether a broad phase picks the pairs.

#include "common/collision/bv_type.h"
#include "common/contact/contact_set.h"
#include "common/core/types.h"
#include "common/sim/effects.h"

namespace hs {

struct SceneOptions {
  /// Simulated time per step, seconds. Finite and > 0.
  double step_s = 1e-3;
  /// The effects this scene allows.
  EffectSet enabled = EffectSet::All();
  ContactMethod method = ContactMethod::kSweep3d;
  BvType bv = BvType::kObbRss;
  /// Touching tolerance relative to a pair's size (ContactQuery); <= 1e-6.
  double relative_tolerance = 1e-9;
  /// The largest force rendered on a tool, newtons. Finite and > 0.
  double force_clamp_n = 10;
  /// The validity radius of each tool's local contact model
  /// (local_model.h), metres, in (0, 1]: the faces within it of the tool
  /// at its proxy pose become the model's planes. 1 cm holds a hand at
  /// 0.1 m/s for a 100 ms round trip; the search's cost grows with its
  /// square on a fine surface.
  double local_model_radius_m = 0.01;
  /// The largest validity radius a tool's device may ask for
  /// (Scene::SetLocalModelRadius), metres, in [local_model_radius_m, 1]:
  /// 4 cm holds a hand at 0.2 m/s for 200 ms.
  double local_model_radius_cap_m = 0.04;
  /// Acceleration of free bodies by gravity, world frame, m/s^2. Finite.
  Vector3d gravity_W = Vector3d(0, 0, -9.81);
  /// How fast a free body's spin dies while it touches something, 1/s
  /// (w decays as exp(-rate t)); finite and >= 0. One impulse point per
  /// contact leaves a body rocking on a face without it; free flight is
  /// not damped.
  double contact_angular_damping_per_s = 20;
  /// Pick the pairs to test by their boxes: FCL's dynamic AABB tree
  /// (BroadPhase) at the step's end poses, or the boxes swept along the
  /// step when continuous collision or sub-stepping is on. False tests
  /// every pair (same results, slower: the oracle of the tests).
  bool broad_phase = true;
  /// The tools of a step run on the scene's worker threads
  /// (Scene::SetThreads) only after a step whose tools' work, summed over
  /// the threads, took more than this share of step_s; in [0, 1]. A
  /// shorter step ends in time on the stepping thread alone, and waking a
  /// worker (a futex wake and wait on each side, two context switches)
  /// costs more of a core than it saves: with 16 remote devices on the
  /// demo scene, about a tenth of a core (docs/scaling.md). 0 hands every
  /// step of more than one job to the workers.
  double parallel_work_share = 0.25;
};

}  // namespace hs
