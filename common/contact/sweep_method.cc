#include "common/contact/sweep_method.h"

namespace hs {

// Placeholder until the method lands: reports touching with zero depth.
ContactSet ReconstructBySweep(const ContactContext& context) {
  ContactSet set;
  set.colliding = true;
  set.direction_W = context.direction_F;
  return set;
}

}  // namespace hs
