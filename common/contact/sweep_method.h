#pragma once
// Internal to common/contact: the exact 3D method of shared/ALGORITHM.md,
// sweep intervals by the separating axis theorem.

#include "common/contact/contact_context.h"
#include "common/contact/contact_set.h"

namespace hs {

/// Runs the 3D sweep method on `context` and returns its ContactSet with
/// every vector and point in F's frame (the caller maps them to world).
ContactSet ReconstructBySweep(const ContactContext& context);

}  // namespace hs
