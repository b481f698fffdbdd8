#include "common/sim/pair_caches.h"

#include <algorithm>

namespace hs {

PairCache& PairCaches::For(ObjectId id) {
  Slot* free = nullptr;
  for (Slot& slot : slots_) {
    if (slot.object == id) {
      slot.used = true;
      return slot.cache;
    }
    if (slot.object < 0 && !free) free = &slot;
  }
  if (!free) free = &slots_.emplace_back();
  free->object = id;
  free->used = true;
  free->cache.Clear();
  return free->cache;
}

void PairCaches::FreeUnused() {
  for (Slot& slot : slots_) {
    if (!slot.used) {
      slot.object = -1;
      slot.cache.Clear();
    }
    slot.used = false;
  }
}

int PairCaches::held() const {
  return static_cast<int>(
      std::count_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.object >= 0; }));
}

}  // namespace hs
