#include "server/snapshot_pool.h"

namespace hs {

SnapshotPool::SnapshotPool() {
  slots_.reserve(kInitialSlots);
  for (size_t k = 0; k < kInitialSlots; ++k) {
    slots_.push_back({std::make_shared<StepSnapshot>(), {}});
  }
}

SnapshotPool::Slot& SnapshotPool::Take() {
  for (size_t k = 0; k < slots_.size(); ++k) {
    Slot& slot = slots_[(next_ + k) % slots_.size()];
    // Only the pool holds it: no stream can take it again, and every
    // stream's reads of it happened before its release. A copy's increment
    // (an acquire-release read-modify-write of the count) pairs with the
    // last holder's releasing decrement; an acquire fence would too, but
    // ThreadSanitizer does not see fences.
    if (slot.snapshot.use_count() == 1) {
      { const std::shared_ptr<StepSnapshot> acquire = slot.snapshot; }
      next_ = (next_ + k + 1) % slots_.size();
      return slot;
    }
  }
  if (slots_.size() >= kMaxPooled) {
    unpooled_.snapshot = std::make_shared<StepSnapshot>();
    return unpooled_;
  }
  slots_.push_back({std::make_shared<StepSnapshot>(), {}});
  next_ = 0;
  return slots_.back();
}

}  // namespace hs
