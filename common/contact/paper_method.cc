#include "common/contact/paper_method.h"

namespace hs {

// Placeholder until the method lands: reports touching with zero depth.
ContactSet ReconstructByProjection(const ContactContext& context) {
  ContactSet set;
  set.colliding = true;
  set.direction_W = context.direction_F;
  return set;
}

}  // namespace hs
