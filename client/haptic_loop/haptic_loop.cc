#include "client/haptic_loop/haptic_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/sim/proxy_slide.h"

namespace hs {
namespace {

// The proxy stops this far (relative to the validity radius on planes, to
// the tool's size on a surface, as the server's proxy) in front of what it
// meets, so that sliding along it does not meet it again at once.
constexpr double kStandOff = 1e-6;

bool Finite(const Isometry3d& X) { return X.matrix().allFinite(); }

ModelMaterial PlaneMaterial(const ConstraintPlane& p) {
  return {p.stiffness_n_per_m, p.damping_ns_per_m, p.static_friction, p.dynamic_friction};
}

bool ValidMaterial(const ModelMaterial& m) {
  return std::isfinite(m.stiffness_n_per_m) && m.stiffness_n_per_m > 0 &&
         std::isfinite(m.damping_ns_per_m) && m.damping_ns_per_m >= 0 &&
         std::isfinite(m.static_friction) && m.static_friction >= 0 &&
         std::isfinite(m.dynamic_friction) && m.dynamic_friction >= 0 &&
         m.dynamic_friction <= m.static_friction;
}

bool ValidTriangles(const std::vector<std::array<int32_t, 3>>& triangles, size_t vertices) {
  return std::all_of(triangles.begin(), triangles.end(), [&](const std::array<int32_t, 3>& t) {
    return std::all_of(t.begin(), t.end(),
                       [&](int32_t i) { return i >= 0 && static_cast<size_t>(i) < vertices; });
  });
}

// A surface's numbers finite and within 1e6, its radius > 0, its indices
// within range, its sizes within the caps (local_model.h).
bool ValidSurface(const ModelSurface& s) {
  // Finite and within the wire's bounds (proto_convert.h's kMaxCoordinate).
  const auto finite = [](const Vector3d& x) {
    return x.allFinite() && x.cwiseAbs().maxCoeff() <= 1e6;
  };
  if (!s.center_W.allFinite() || !std::isfinite(s.radius_m) || !(s.radius_m > 0)) return false;
  if (!s.has_body()) return true;
  if (s.tool_vertices_T.size() > static_cast<size_t>(kMaxToolHullVertices) ||
      s.tool_triangles.size() > static_cast<size_t>(kMaxToolHullTriangles) ||
      s.triangles.size() > static_cast<size_t>(kMaxSurfaceTriangles) ||
      s.materials.size() > static_cast<size_t>(kMaxSurfaceMaterials)) {
    return false;
  }
  return std::all_of(s.tool_vertices_T.begin(), s.tool_vertices_T.end(), finite) &&
         std::all_of(s.vertices_W.begin(), s.vertices_W.end(), finite) &&
         ValidTriangles(s.tool_triangles, s.tool_vertices_T.size()) &&
         ValidTriangles(s.triangles, s.vertices_W.size()) &&
         s.triangle_materials.size() == s.triangles.size() &&
         std::all_of(
             s.triangle_materials.begin(), s.triangle_materials.end(),
             [&](int32_t m) { return m >= 0 && static_cast<size_t>(m) < s.materials.size(); }) &&
         std::all_of(s.materials.begin(), s.materials.end(), ValidMaterial);
}

// Whether `held` has the faces of the surface `named` names: the same
// revision, centre and radius.
bool SameSurface(const std::shared_ptr<const ModelSurface>& held, const ModelSurface& named) {
  return held && held->has_body() && held->revision == named.revision &&
         held->center_W == named.center_W && held->radius_m == named.radius_m;
}

bool ValidModel(const LocalModel& m) {
  if (!Finite(m.X_WP) || !m.touch_point_W.allFinite() || !std::isfinite(m.validity_radius_m) ||
      !(m.validity_radius_m > 0) || !std::isfinite(m.force_clamp_n) || !(m.force_clamp_n > 0)) {
    return false;
  }
  return std::all_of(m.planes.begin(), m.planes.end(), [](const ConstraintPlane& p) {
    return p.point_W.allFinite() && p.normal_W.allFinite() && p.tool_point_W.allFinite() &&
           std::abs(p.normal_W.norm() - 1) <= 1e-6 && std::isfinite(p.gap_m) && p.gap_m >= 0 &&
           ValidMaterial(PlaneMaterial(p));
  });
}

}  // namespace

HapticLoop::HapticLoop(const HapticLoopOptions& options)
    : options_(options), history_(std::max(options.history_ticks, 1)) {}

bool HapticLoop::SetModel(const LocalModel& model) {
  // A surface the loop holds was checked when it came.
  const bool held_surface =
      model.surface && (model.surface == surface_ || model.surface == pending_model_.surface);
  if (!ValidModel(model) || (model.surface && !held_surface && !ValidSurface(*model.surface))) {
    ++rejected_models_;
    return false;
  }
  // A frame may carry the model the loop has already taken: taking it
  // again would correct the proxy's drift twice.
  const LocalModel& newest = has_pending_model_ ? pending_model_ : model_;
  if (model.revision != 0 && (has_model_ || has_pending_model_) &&
      model.revision == newest.revision) {
    return true;
  }
  // A model that names its surface alone shares the body the loop already
  // has (or its last pending model brought).
  std::shared_ptr<const ModelSurface> body;
  if (model.surface && !model.surface->has_body()) {
    for (const auto* held : {&pending_model_.surface, &surface_}) {  // newest first
      if (SameSurface(*held, *model.surface)) {
        body = *held;
        break;
      }
    }
    // A model with no planes beside its surface (a device that reads
    // surfaces alone) whose faces did not come: the newest surface the loop
    // holds serves within its own sphere, as its objects have not moved
    // (had they, the proxy restarts where it lies in a face). With none,
    // the loop meets nothing and asks for a fresh model (Step).
    if (!body && model.planes.empty()) {
      for (const auto* held : {&pending_model_.surface, &surface_}) {
        if (*held && (*held)->has_body()) {
          body = *held;
          break;
        }
      }
    }
  }
  pending_model_ = model;
  if (body) pending_model_.surface = std::move(body);
  has_pending_model_ = true;
  return true;
}

HapticLoop::Hit HapticLoop::FirstHit(const Vector3d& p, const Vector3d& v) const {
  const Vector3d P0 = model_.X_WP.translation();
  const int count = static_cast<int>(model_.planes.size());
  const auto ahead = [&](const ConstraintPlane& plane) {
    return plane.gap_m + plane.normal_W.dot(p - P0);
  };
  // The object's planes the move meets one by one: where the tool's
  // distance in front of a plane falls to zero. An object with separating
  // planes that the tool is in front of takes only those, below.
  const auto separated = [&](int32_t object) {
    for (const ConstraintPlane& plane : model_.planes) {
      if (plane.separating && plane.object == object && ahead(plane) > 0) return true;
    }
    return false;
  };
  Hit first;
  for (int i = 0; i < count; ++i) {
    const ConstraintPlane& plane = model_.planes[i];
    if (separated(plane.object)) continue;
    const double approach = plane.normal_W.dot(v);
    if (approach >= 0) continue;
    const double t = std::max(ahead(plane), 0.0) / -approach;
    if (t <= 1 && t < first.t) first = {i, t};
  }
  // A separated object: the move meets it where it enters the region
  // behind every one of its separating planes, through the plane it
  // crosses last (a segment clipped by a convex region).
  for (int i = 0; i < count; ++i) {
    const ConstraintPlane& lead = model_.planes[i];
    if (!lead.separating || !separated(lead.object)) continue;
    bool first_of_object = true;
    for (int k = 0; k < i && first_of_object; ++k) {
      first_of_object = !(model_.planes[k].separating && model_.planes[k].object == lead.object);
    }
    if (!first_of_object) continue;
    double enter = 0;
    double leave = std::numeric_limits<double>::infinity();
    int through = -1;
    for (int k = i; k < count; ++k) {
      const ConstraintPlane& plane = model_.planes[k];
      if (!plane.separating || plane.object != lead.object) continue;
      const double d = ahead(plane);
      const double approach = plane.normal_W.dot(v);
      if (d > 0) {
        if (approach >= 0) {
          enter = std::numeric_limits<double>::infinity();
          break;
        }
        if (d / -approach > enter) {
          enter = d / -approach;
          through = k;
        }
      } else if (approach > 0) {
        leave = std::min(leave, -d / approach);
      }
    }
    if (through >= 0 && enter <= 1 && enter <= leave && enter < first.t) first = {through, enter};
  }
  return first;
}

HapticLoop::Meet HapticLoop::FirstMeet(const Vector3d& p, const Vector3d& v) const {
  if (on_surface_) {
    const SurfaceSweep::Touch touch = sweep_.First(p, v);
    if (touch.triangle < 0) return {};
    return {touch.triangle, touch.t, touch.normal_W, sweep_.Material(touch.triangle)};
  }
  const Hit hit = FirstHit(p, v);
  if (hit.plane < 0) return {};
  const ConstraintPlane& plane = model_.planes[hit.plane];
  return {hit.plane, hit.t, plane.normal_W, PlaneMaterial(plane)};
}

bool HapticLoop::LeftPlane(const Vector3d& p, int plane) const {
  if (on_surface_) return false;
  const ConstraintPlane& on = model_.planes[plane];
  if (!on.separating) return false;
  const Vector3d P0 = model_.X_WP.translation();
  const double stand_off = kStandOff * model_.validity_radius_m;
  return std::any_of(model_.planes.begin(), model_.planes.end(), [&](const ConstraintPlane& other) {
    return &other != &on && other.separating && other.object == on.object &&
           other.gap_m + other.normal_W.dot(p - P0) > 2 * stand_off;
  });
}

HapticLoop::Meet HapticLoop::MoveProxy(const Vector3d& target, bool friction) {
  const double stand_off = StandOff();
  Vector3d p = proxy_;
  Vector3d goal = target;
  Meet touched;
  for (int slide = 0; slide <= options_.max_slides; ++slide) {
    const Vector3d v = goal - p;
    if (v.norm() <= stand_off * 1e-3) break;
    const Meet first = FirstMeet(p, v);
    if (first.index < 0) {
      p = goal;
      // Slid past the edge of a separating plane's face: the tool is in
      // front of another of its object's separating planes, free of the
      // object, and goes on toward the target.
      if (touched.index >= 0 && goal != target && slide < options_.max_slides &&
          LeftPlane(p, touched.index)) {
        touched = {};
        goal = target;
        continue;
      }
      break;
    }
    const Vector3d& n = first.normal;
    p += first.t * v + stand_off * n;
    touched = first;
    // Slide toward the target as the server's proxy does (proxy_slide.h).
    const std::optional<Vector3d> next =
        SlideGoal(p, target, n,
                  friction && model_.friction
                      ? std::optional<SlideFriction>(
                            {first.material.static_friction, first.material.dynamic_friction})
                      : std::nullopt);
    if (!next) break;
    goal = *next;
  }
  proxy_ = p;
  return touched;
}

HapticOutput HapticLoop::Render(const Meet& touched, const Vector3d& device, const Vector3d& v_WD,
                                bool held) const {
  HapticOutput out;
  out.p_WP = InValidity(proxy_);
  if (touched.index < 0) return out;
  const Vector3d& n = touched.normal;
  out.touching = true;
  // As the server's common/sim/tool_force.h: spring to the proxy, damper
  // along the normal, clamped; the lever is tool-fixed.
  out.force_W = touched.material.stiffness_n_per_m * (out.p_WP - device) -
                touched.material.damping_ns_per_m * v_WD.dot(n) * n;
  // There the model knows no more of the surface than that the tool is
  // behind this plane: it pushes out along the normal, and neither drags
  // the hand back toward the sphere nor holds it by friction.
  if (held) out.force_W = n * n.dot(out.force_W);
  if (out.force_W.norm() > model_.force_clamp_n) {
    out.force_W *= model_.force_clamp_n / out.force_W.norm();
    out.clamped = true;
  }
  if (on_surface_) {
    // The server's touching point at the model's proxy while it touched
    // (the lever is tool-fixed), else where the tool reaches against n.
    const Vector3d lever = model_.touching
                               ? Vector3d(model_.touch_point_W - model_.X_WP.translation())
                               : Vector3d(sweep_.TouchPoint(out.p_WP, n) - out.p_WP);
    out.torque_W = lever.cross(out.force_W);
    return out;
  }
  const Vector3d& lever_end =
      model_.touching ? model_.touch_point_W : model_.planes[touched.index].tool_point_W;
  out.torque_W = (lever_end - model_.X_WP.translation()).cross(out.force_W);
  return out;
}

void HapticLoop::Record(const Vector3d& device, const Vector3d& proxy) {
  history_[history_next_] = {device, proxy};
  history_next_ = (history_next_ + 1) % static_cast<int>(history_.size());
  history_size_ = std::min(history_size_ + 1, static_cast<int>(history_.size()));
}

int HapticLoop::FindInHistory(const Vector3d& p_WD) const {
  const int n = static_cast<int>(history_.size());
  for (int k = 0; k < history_size_; ++k) {
    const int i = (history_next_ - 1 - k + n) % n;
    if (history_[i].device == p_WD) return i;
  }
  return -1;
}

void HapticLoop::SwitchModel(const Vector3d& device, Vector3d kept) {
  const Vector3d p_WD = pending_model_.p_WD;
  const bool first = !has_model_;
  std::swap(model_, pending_model_);
  has_pending_model_ = false;
  has_model_ = true;
  const Vector3d P0 = model_.X_WP.translation();
  proxy_ = P0;
  on_surface_ = model_.surface && model_.surface->has_body();
  if (on_surface_) {
    if (surface_ != model_.surface) {
      surface_ = model_.surface;
      sweep_.Set(*surface_);
      oriented_ = false;
    }
    // The surface is the objects' own: the proxy the loop has is as good
    // as the server's, and stays where it is while it is within the
    // surface's sphere and outside every face; else it restarts at the
    // server's.
    Orient(last_orientation_);
    const Sphere sphere = ValiditySphere();
    if ((kept - sphere.center).norm() <= sphere.radius && !sweep_.Overlaps(kept, StandOff())) {
      proxy_ = kept;
    } else if (!first) {
      ++restarted_models_;
    }
    return;
  }
  // The loop's own proxy when the device was where the model was taken:
  // this tick's (no latency) or one in the history; else a restart at the
  // server's proxy.
  const bool now = p_WD == device;
  const int then = now ? -1 : FindInHistory(p_WD);
  if (!now && then < 0) {
    ++restarted_models_;
    return;
  }
  // Where the loop's proxy is now, moved by the server's correction of
  // where it was then; reached from the server's proxy, so that it ends
  // in front of every plane (frictionless: this is no motion of the tool).
  const Vector3d goal = kept + (P0 - (now ? kept : history_[then].proxy));
  MoveProxy(goal, false);
  if (now) return;
  // The ticks since the model's were rendered from the uncorrected proxy:
  // they take the correction too, so that the next model's does not count
  // it again.
  const Vector3d moved = proxy_ - kept;
  const int n = static_cast<int>(history_.size());
  for (int i = (then + 1) % n; i != history_next_; i = (i + 1) % n) history_[i].proxy += moved;
}

void HapticLoop::KeepPassive(HapticOutput& out, const Vector3d& v_WD) {
  // What the contact may hand back is what its spring holds (and a small
  // reserve): the energy friction and the dampers took from the hand is
  // gone, and never pays for a later kick. In free space that is nothing.
  // A debt stays until it is paid back.
  work_on_hand_j_ = std::max(work_on_hand_j_, -(stored_j_ + options_.passivity_reserve_j));
  const double dt = options_.tick_s;
  const double speed2 = v_WD.squaredNorm();
  const double work_after = work_on_hand_j_ + out.force_W.dot(v_WD) * dt;
  Vector3d wanted = Vector3d::Zero();
  if (work_after > 0 && speed2 > 0) {
    wanted = -std::min(work_after / (speed2 * dt), options_.max_passivity_damping_ns_per_m) * v_WD;
  }
  // The damper comes and goes no faster than a model switch may change
  // the force: a damper switched on at once against a fast hand would be
  // a kick of its own. What it lags by is observed next tick and paid then.
  const Vector3d change = wanted - passivity_force_;
  const double step = options_.max_switch_step_n;
  passivity_force_ += change.norm() > step ? Vector3d(change * (step / change.norm())) : change;
  if (passivity_force_.isZero()) return;
  const Vector3d before = out.force_W;
  out.force_W += passivity_force_;
  if (has_model_ && out.force_W.norm() > model_.force_clamp_n) {
    out.force_W *= model_.force_clamp_n / out.force_W.norm();
    out.clamped = true;
  }
  ++passivity_ticks_;
  passivity_dissipated_j_ += (before - out.force_W).dot(v_WD) * dt;
}

double HapticLoop::StandOff() const {
  // On a surface, as the server's proxy: relative to the tool's size.
  return on_surface_ ? kStandOff * sweep_.tool_size() : kStandOff * model_.validity_radius_m;
}

HapticLoop::Sphere HapticLoop::ValiditySphere() const {
  if (on_surface_) return {surface_->center_W, surface_->radius_m};
  return {model_.X_WP.translation(), model_.validity_radius_m};
}

void HapticLoop::Orient(const Matrix3d& R_WT) {
  if (!on_surface_ || (oriented_ && R_WT == oriented_to_)) return;
  sweep_.Orient(R_WT);
  oriented_to_ = R_WT;
  oriented_ = true;
}

Vector3d HapticLoop::InValidity(const Vector3d& point) const {
  const Sphere sphere = ValiditySphere();
  const Vector3d out = point - sphere.center;
  const double r = sphere.radius;
  return out.norm() > r ? Vector3d(sphere.center + out * (r / out.norm())) : point;
}

HapticOutput HapticLoop::Step(const Vector3d& device, const Vector3d& v_WD) {
  const Meet touched = MoveProxy(device, true);
  const Sphere sphere = ValiditySphere();
  const bool held = (proxy_ - sphere.center).norm() > sphere.radius;
  HapticOutput out = Render(touched, device, v_WD, held);
  // A model whose surface's faces the loop lacks, with no planes beside,
  // holds nowhere.
  out.beyond_validity = (device - sphere.center).norm() > sphere.radius ||
                        (model_.surface && !on_surface_ && model_.planes.empty());
  // The energy the touched face's spring holds (past the sphere, its
  // push along the normal only).
  stored_j_ = 0;
  if (touched.index >= 0) {
    const Vector3d stretch = out.p_WP - device;
    const double along = touched.normal.dot(stretch);
    stored_j_ =
        0.5 * touched.material.stiffness_n_per_m * (held ? along * along : stretch.squaredNorm());
  }
  return out;
}

HapticOutput HapticLoop::Tick(const Isometry3d& X_WD) {
  if (!Finite(X_WD)) {
    ++rejected_poses_;
    return last_;
  }
  const Vector3d device = X_WD.translation();
  last_orientation_ = X_WD.linear();
  Orient(last_orientation_);
  // The work last tick's force did on the hand as it moved since.
  if (has_last_device_) work_on_hand_j_ += last_.force_W.dot(device - last_device_);
  const Vector3d v_WD =
      has_last_device_ ? Vector3d((device - last_device_) / options_.tick_s) : Vector3d::Zero();
  last_device_ = device;
  has_last_device_ = true;
  HapticOutput out;
  if (has_pending_model_ && on_surface_ && pending_model_.surface &&
      pending_model_.surface->has_body()) {
    // From a surface to the next: the same objects, so the proxy stays
    // and the force goes on; only a restart's step is spread.
    const int64_t restarts = restarted_models_;
    SwitchModel(device, proxy_);
    out = Step(device, v_WD);
    if (restarted_models_ != restarts) switch_offset_ += last_rendered_ - out.force_W;
  } else if (has_pending_model_) {
    // What the old model renders at this pose, against what the new one
    // does from the server's proxy: that step, not the hand's motion, is
    // what gets spread over the next ticks.
    const Vector3d before = has_model_ ? Step(device, v_WD).force_W : last_.force_W;
    SwitchModel(device, has_model_ ? proxy_ : device);
    out = Step(device, v_WD);
    switch_offset_ += before - out.force_W;
  } else if (has_model_) {
    out = Step(device, v_WD);
  } else {
    proxy_ = device;
    out.p_WP = device;
    stored_j_ = 0;
  }
  if (out.beyond_validity) ++beyond_validity_ticks_;
  last_rendered_ = out.force_W;
  const double left = switch_offset_.norm();
  if (left <= options_.max_switch_step_n) {
    switch_offset_.setZero();
  } else {
    switch_offset_ *= (left - options_.max_switch_step_n) / left;
  }
  out.force_W += switch_offset_;
  if (has_model_ && out.force_W.norm() > model_.force_clamp_n) {
    out.force_W *= model_.force_clamp_n / out.force_W.norm();
    out.clamped = true;
  }
  KeepPassive(out, v_WD);
  Record(device, proxy_);
  last_ = out;
  return out;
}

}  // namespace hs
