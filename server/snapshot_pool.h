#pragma once
// Step snapshots for reuse. A snapshot that every stream has let go of is
// written over for a later step, frame included (CopyFrame keeps its
// storage), so that once the pool holds as many snapshots as are in flight
// a step allocates none.

#include <memory>
#include <vector>

#include "common/sim/frame_storage.h"
#include "server/step_snapshot.h"

namespace hs {

class SnapshotPool {
 public:
  /// Starts with kInitialSlots snapshots, taken in turn: a steady run that
  /// never holds more at once warms them all and then allocates nothing.
  SnapshotPool();

  struct Slot {
    std::shared_ptr<StepSnapshot> snapshot;
    /// What CopyFrame keeps for the snapshot's later frames.
    FrameCopyStorage storage;
  };

  /// A slot whose snapshot no one else holds (the pool grows by one when
  /// every snapshot is held, up to kMaxPooled; past it the slot is fresh
  /// and not kept). Valid until the next Take. One thread takes.
  Slot& Take();

  size_t size() const { return slots_.size(); }

  static constexpr size_t kInitialSlots = 8;
  static constexpr size_t kMaxPooled = 512;

 private:
  std::vector<Slot> slots_;
  size_t next_ = 0;  // where the search for a free slot starts
  Slot unpooled_;
};

}  // namespace hs
