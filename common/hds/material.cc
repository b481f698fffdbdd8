#include "common/hds/material.h"

#include <string>

#include "absl/strings/str_cat.h"

namespace hs {
namespace {

absl::Status Invalid(const Material& m, const char* field, double value, const std::string& rule) {
  return absl::InvalidArgumentError(
      absl::StrCat("material '", m.name, "': ", field, " = ", value, " must be ", rule));
}

}  // namespace

absl::Status ValidateMaterial(const Material& m) {
  if (!(m.stiffness_n_per_m > 0 && m.stiffness_n_per_m <= kMaxStiffnessNPerM)) {
    return Invalid(m, "stiffness_n_per_m", m.stiffness_n_per_m,
                   absl::StrCat("> 0 and <= ", kMaxStiffnessNPerM));
  }
  if (!(m.damping_ns_per_m >= 0 && m.damping_ns_per_m <= kMaxDampingNsPerM)) {
    return Invalid(m, "damping_ns_per_m", m.damping_ns_per_m,
                   absl::StrCat("in [0, ", kMaxDampingNsPerM, "]"));
  }
  if (!(m.static_friction >= 0 && m.static_friction <= kMaxFriction)) {
    return Invalid(m, "static_friction", m.static_friction,
                   absl::StrCat("in [0, ", kMaxFriction, "]"));
  }
  if (!(m.dynamic_friction >= 0 && m.dynamic_friction <= m.static_friction)) {
    return Invalid(m, "dynamic_friction", m.dynamic_friction, ">= 0 and <= static_friction");
  }
  return absl::OkStatus();
}

}  // namespace hs
