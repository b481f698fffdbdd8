#pragma once
// One tool's pair caches (common/collision/pair_cache.h): one per object
// whose contact set the tool's last step reconstructed, so that the next
// step's queries start from what that one learned. Kept only while the
// contact set stage runs and the pair stays in contact: a scene that needs
// no contact sets keeps none.

#include <vector>

#include "common/collision/pair_cache.h"
#include "common/sim/step_frame.h"

namespace hs {

class PairCaches {
 public:
  /// The cache of the pair with object `id`, marked in use this step; a
  /// new pair gets a free cache (storage kept from an earlier pair). Valid
  /// until the next call.
  PairCache& For(ObjectId id);
  /// Ends a step: the caches not used in it are freed.
  void FreeUnused();
  /// Caches held for pairs now.
  int held() const;

 private:
  struct Slot {
    ObjectId object = -1;  // -1: free
    bool used = false;
    PairCache cache;
  };
  std::vector<Slot> slots_;
};

}  // namespace hs
