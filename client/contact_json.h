#pragma once
// ContactSet as JSON, for hapticctl's local commands.

#include <nlohmann/json.hpp>

#include "common/contact/contact_set.h"

namespace hs::cli {

/// Every field of `set`; vectors as [x, y, z] arrays, kinds as "vertex",
/// "edge", "face" or "none", infinite plane depths as null.
nlohmann::ordered_json ContactSetToJson(const ContactSet& set);

/// A vector as [x, y, z].
nlohmann::ordered_json Vector3Json(const Vector3d& v);

/// "vertex", "edge", "face" or "none".
const char* FeatureKindName(FeatureKind kind);

}  // namespace hs::cli
