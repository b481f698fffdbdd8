#pragma once
// The force a haptic device renders: a spring from the device to its proxy
// (the god object kept out of the objects) and a damper along the touched
// surface's normal, with its torque.

#include "common/core/types.h"
#include "common/hds/material.h"

namespace hs {

/// Where the proxy touches, and how the device moves.
struct ToolContact {
  /// Origins of the device (X_WD) and of the proxy (X_WP), world frame, metres.
  Vector3d p_WD = Vector3d::Zero();
  Vector3d p_WP = Vector3d::Zero();
  /// The device's velocity over the last step, world frame, m/s.
  Vector3d v_WD = Vector3d::Zero();
  /// Unit normal of the touched surface, world frame, pointing out of it.
  Vector3d normal_W = Vector3d::UnitZ();
  /// The touching point of the tool in the proxy's pose, world frame, metres.
  Vector3d p_WC = Vector3d::Zero();
};

/// Force and torque on the device, world frame, N and N*m.
struct ToolForce {
  Vector3d force_W = Vector3d::Zero();
  /// About the tool's origin: the lever runs from the proxy's origin to the
  /// touching point. The proxy keeps the device's orientation, so that is
  /// the same tool-fixed lever as from the device's origin: the torque to
  /// render about the device origin.
  Vector3d torque_W = Vector3d::Zero();
  /// The force was scaled down to the clamp.
  bool clamped = false;
};

/// The material a tool's face `own` meets another tool's face `touched`
/// with: their stiffnesses and their dampings in series (two springs
/// pressed together: 1/k = 1/k_own + 1/k_touched); the friction is the
/// touched face's, as the proxy slides with it (proxy.h), and the name
/// empty (no allocation per step).
Material TouchingMaterial(const Material& own, const Material& touched);

/// F = k (p_WP - p_WD) - c (v_WD . n) n with the touched material's k
/// (stiffness_n_per_m) and c (damping_ns_per_m), scaled down to
/// `clamp_n` newtons when longer; torque = (p_WC - p_WP) x F.
ToolForce SpringDamperForce(const Material& material, const ToolContact& contact, double clamp_n);

/// `force` plus `reaction` (a force and a torque, world frame, N and N*m,
/// e.g. another tool's push turned round), scaled down to `clamp_n` again
/// (clamped stays set once set).
ToolForce WithReaction(ToolForce force, const ToolForce& reaction, double clamp_n);

/// `force` with the reaction of the free bodies the tool pushed this step:
/// they push back with the impulse they took (`push_impulse_W`, world
/// frame, N*s) spread over the step of `step_s` seconds, F - J / dt,
/// scaled down to `clamp_n` again (clamped stays set once set). The
/// torque is the spring's.
ToolForce WithPushReaction(ToolForce force, const Vector3d& push_impulse_W, double step_s,
                           double clamp_n);

}  // namespace hs
