#include "common/hds/material.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

absl::Status Invalid(const Material& m, const char* field, double value, const char* rule) {
  return absl::InvalidArgumentError(
      absl::StrCat("material '", m.name, "': ", field, " = ", value, " must be ", rule));
}

}  // namespace

absl::Status ValidateMaterial(const Material& m) {
  if (!(std::isfinite(m.stiffness_n_per_m) && m.stiffness_n_per_m > 0)) {
    return Invalid(m, "stiffness_n_per_m", m.stiffness_n_per_m, "finite and > 0");
  }
  if (!(std::isfinite(m.damping_ns_per_m) && m.damping_ns_per_m >= 0)) {
    return Invalid(m, "damping_ns_per_m", m.damping_ns_per_m, "finite and >= 0");
  }
  if (!(std::isfinite(m.static_friction) && m.static_friction >= 0)) {
    return Invalid(m, "static_friction", m.static_friction, "finite and >= 0");
  }
  if (!(std::isfinite(m.dynamic_friction) && m.dynamic_friction >= 0 &&
        m.dynamic_friction <= m.static_friction)) {
    return Invalid(m, "dynamic_friction", m.dynamic_friction,
                   "finite, >= 0 and <= static_friction");
  }
  return absl::OkStatus();
}

}  // namespace hs
