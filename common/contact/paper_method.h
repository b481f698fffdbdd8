#pragma once
// Internal to common/contact: the paper's contact reconstruction by
// projection onto the xy, yz and xz planes (s.4 and appendix), as
// docs/algorithm.md reads it.

#include "common/contact/contact_context.h"
#include "common/contact/contact_set_f.h"

namespace hs {

/// Runs the paper's method on `context`: its contact in F's frame.
ContactSetF ReconstructByProjection(const ContactContext& context);

}  // namespace hs
