#pragma once
// Writing step frames over old ones without allocating: the contact sets
// of pairs a frame no longer has wait in a spare list, their vectors'
// storage kept, for the pairs of later frames.

#include <cstddef>
#include <vector>

#include "common/sim/step_frame.h"

namespace hs {

/// Empties `contacts`, moving each pair's contact set into `spare`.
void ClearPairContacts(std::vector<PairContact>& contacts, std::vector<ContactSet>& spare);

/// Appends a pair whose contact set (cleared, ClearContactSet) comes from
/// `spare` when it has one.
PairContact& AddPairContact(std::vector<PairContact>& contacts, std::vector<ContactSet>& spare);

/// What one frame copy keeps between copies: spare contact sets, and the
/// longest feature and point lists any contact set copied so far had.
struct FrameCopyStorage {
  std::vector<ContactSet> spare;
  size_t most_features = 0;
  size_t most_points = 0;
};

/// Copies `from` over `to`. The pairs are first made as many as `from`'s
/// (through `storage.spare`) and every list given room for the longest
/// seen so far, then copied element by element into that storage: once
/// `to` has been written after the largest contact first came by, a copy
/// allocates nothing, whichever frames `to` held before.
void CopyFrame(const StepFrame& from, StepFrame& to, FrameCopyStorage& storage);

}  // namespace hs
