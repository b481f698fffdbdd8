#pragma once
// Building one object's SideContact from its contact features (paper s.4:
// neighbouring contact vertices on one edge make an edge contact, on one
// face a face contact).

#include <span>

#include "common/contact/contact_set.h"
#include "common/hds/haptic_object.h"

namespace hs {

/// The SideContact of `object` given its contact vertices and the edges and
/// faces touched inside. Adds every edge whose two ends are contact
/// vertices and every face whose three corners are, sorts, removes repeats,
/// and sets kind to the highest dimension present. Writes `side` over,
/// keeping its vectors' storage (no allocation once they are large enough).
void AggregateSide(const HapticObject& object, std::span<const VertexId> vertices,
                   std::span<const EdgeId> touched_edges, std::span<const FaceId> touched_faces,
                   SideContact& side);

}  // namespace hs
