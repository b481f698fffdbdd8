#pragma once
// Internal to common/contact: the exact 3D method of docs/algorithm.md,
// sweep intervals by the separating axis theorem.

#include "common/contact/contact_context.h"
#include "common/contact/contact_set_f.h"

namespace hs {

/// Runs the 3D sweep method on `context`: its contact in F's frame, written
/// over `set` (every field; its vectors' storage is kept).
void ReconstructBySweep(const ContactContext& context, ContactSetF& set);

}  // namespace hs
